#include "spectral/reports/reflectance_report.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "spectral/colour_spaces/chromatic_adaptation.h"
#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/error.h"
#include "spectral/spectra/spectrum_values_check.h"
#include "spectral/library/tabulated_colorimetry.h"
#include "spectral/colorimetry/tristimulus_method_json.h"
#include "spectral/reports/report_format.h"

namespace rimu {
namespace {

constexpr const char* kColorCheckerFile = "spectra/reflectances/colorchecker_classic_babelcolor_avg_10nm.csv";

std::string spaced(std::string column) {
  std::replace(column.begin(), column.end(), '_', ' ');
  return column;
}

nlohmann::ordered_json colour_json(const ReflectanceColour& c) {
  nlohmann::ordered_json j;
  j["description"] = c.description;
  add_tristimulus_method_json(j, c.method, c.e308_table);
  j["xyz"] = {c.xyz.x, c.xyz.y, c.xyz.z};
  j["xyY"] = {c.xy.x, c.xy.y, c.xyz.y};
  j["white_xyz"] = {c.white.x, c.white.y, c.white.z};
  j["lab"] = {c.lab.l, c.lab.a, c.lab.b};
  j["srgb_encoded"] = {c.srgb_encoded.r, c.srgb_encoded.g, c.srgb_encoded.b};
  j["srgb_in_gamut"] = c.srgb_in_gamut;
  return j;
}

void colour_text(std::ostringstream& out, const std::string& label, const ReflectanceColour& c) {
  out << label << c.description << "\n";
  out << format_numbers("  XYZ              %.4f %.4f %.4f\n", c.xyz.x, c.xyz.y, c.xyz.z);
  out << format_numbers("  xyY              %.5f %.5f %.4f\n", c.xy.x, c.xy.y, c.xyz.y);
  out << format_numbers("  CIELAB           %.3f %.3f %.3f\n", c.lab.l, c.lab.a, c.lab.b);
  out << format_numbers("  sRGB (encoded)   %.4f %.4f %.4f", c.srgb_encoded.r, c.srgb_encoded.g, c.srgb_encoded.b)
      << format_numbers("   8-bit %.0f %.0f %.0f", 255 * c.srgb_encoded.r, 255 * c.srgb_encoded.g, 255 * c.srgb_encoded.b)
      << (c.srgb_in_gamut ? "" : "   (outside sRGB: clipped)") << "\n";
}

}  // namespace

TabulatedSpectrum load_reflectance_csv(const std::filesystem::path& path, const std::string& column) {
  const CsvTable table = CsvTable::read(path);
  if (table.column_count() < 2)
    throw InputError({path.string(), 0, ""}, "needs a wavelength_nm column and at least one reflectance column");
  const std::string name = column.empty() ? table.header()[1] : column;
  const size_t index = table.column_index(name);
  check_reflectance_factors(table.numbers(index),
                            [&](size_t row) { return SourceLocation{path.string(), table.line_of_row(row), name}; });
  return TabulatedSpectrum::from_csv(table, name, Extrapolation::clamp);
}

TabulatedSpectrum colorchecker_patch(SpectralLibrary& library, const std::string& name, const SourceLocation& where) {
  const CsvTable& table = library.table(kColorCheckerFile);
  for (size_t c = 1; c < table.column_count(); ++c) {
    const std::string& column = table.header()[c];
    if (name == column || name == spaced(column)) {
      TabulatedSpectrum s = TabulatedSpectrum::from_csv(table, column, Extrapolation::clamp);
      return TabulatedSpectrum(s.wavelengths_nm(), s.values(), Extrapolation::clamp,
                               "ColorChecker '" + spaced(column) + "' (BabelColor average, 10 nm)");
    }
  }
  std::string known;
  for (size_t c = 1; c < table.column_count(); ++c) known += (c == 1 ? "" : ", ") + spaced(table.header()[c]);
  throw InputError(where, "unknown ColorChecker patch '" + name + "'; the patches are: " + known);
}

ReflectanceColour measure_reflectance(const TabulatedSpectrum& sample, const ReflectanceConditions& conditions,
                                      SpectralLibrary& library) {
  library.illuminant(conditions.illuminant);  // an unknown name fails here, listing the known ones
  const TristimulusMethod method = conditions.method.value_or(default_tristimulus_method(sample));
  ReflectanceColour c;
  c.description = sample.describe();
  c.method = std::string(method_name(method));
  if (method == TristimulusMethod::astm_e308) c.e308_table = conditions.e308_table;
  c.xyz = reflectance_xyz(sample, conditions.illuminant, conditions.observer, method, library, conditions.e308_table);
  c.xy = chromaticity_of(c.xyz);
  c.white = perfect_diffuser_xyz(sample, conditions.illuminant, conditions.observer, method, library,
                                 conditions.e308_table);
  c.lab = lab_of(c.xyz, c.white);
  // sRGB is defined for a D65 white: adapt the illuminant's white there (Bradford, as ICC practice does).
  const RgbColourSpace& srgb = RgbColourSpace::named("srgb-linear");
  const Xyz white_1{c.white.x / 100, c.white.y / 100, c.white.z / 100};
  const Matrix3 cat = chromatic_adaptation_matrix(white_1, white_point_xyz(srgb), CatMethod::bradford);
  const Rgb linear = srgb.from_xyz(cat.apply(Xyz{c.xyz.x / 100, c.xyz.y / 100, c.xyz.z / 100}));
  auto encode = [&](double v) {
    if (v < -1e-9 || v > 1 + 1e-9) c.srgb_in_gamut = false;
    return srgb_encode(std::clamp(v, 0.0, 1.0));
  };
  c.srgb_encoded = {encode(linear.r), encode(linear.g), encode(linear.b)};
  return c;
}

ReflectanceReport analyse_reflectance(const TabulatedSpectrum& sample, const TabulatedSpectrum* reference,
                                      const ReflectanceConditions& conditions, SpectralLibrary& library) {
  ReflectanceReport r;
  r.illuminant = conditions.illuminant;
  r.observer = library.observer(conditions.observer).name;
  r.sample = measure_reflectance(sample, conditions, library);
  if (reference) {
    r.reference = measure_reflectance(*reference, conditions, library);
    r.delta_e_1976 = delta_e_1976(r.sample.lab, r.reference->lab);
    r.delta_e_2000 = delta_e_2000(r.sample.lab, r.reference->lab);
  }
  return r;
}

std::string reflectance_report_text(const ReflectanceReport& r) {
  std::ostringstream out;
  out << "illuminant         " << r.illuminant << " (white: its perfect reflecting diffuser, Y = 100)\n";
  out << "observer           " << r.observer << "\n";
  out << "tristimulus method " << r.sample.method << "\n";
  if (r.sample.e308_table) out << "e308 weights       " << e308_table_description(*r.sample.e308_table) << "\n";
  colour_text(out, "sample             ", r.sample);
  if (r.reference) {
    colour_text(out, "reference          ", *r.reference);
    out << format_numbers("ΔE*ab (1976)       %.3f\nΔE00 (CIEDE2000)   %.3f\n", r.delta_e_1976, r.delta_e_2000);
  }
  return out.str();
}

std::string reflectance_report_json(const ReflectanceReport& r) {
  nlohmann::ordered_json j;
  j["illuminant"] = r.illuminant;
  j["observer"] = r.observer;
  j["sample"] = colour_json(r.sample);
  if (r.reference) {
    j["reference"] = colour_json(*r.reference);
    j["delta_e_1976"] = r.delta_e_1976;
    j["delta_e_2000"] = r.delta_e_2000;
  }
  return j.dump(2) + "\n";
}

}  // namespace rimu
