#include "spectral/reports/spectrum_report.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/error.h"
#include "spectral/photometry/photometry.h"
#include "spectral/library/tabulated_colorimetry.h"
#include "spectral/colorimetry/tristimulus_method_json.h"
#include "spectral/reports/report_format.h"

namespace rimu {
namespace {

Rgb colour_at_unit_luminance(const Xyz& xyz, const RgbColourSpace& space) {
  if (xyz.y <= 0.0) return {};
  return space.from_xyz({xyz.x / xyz.y, 1.0, xyz.z / xyz.y});
}

}  // namespace

SpectrumReport analyse_spectrum(const SpectrumSource& source, SpectralLibrary& library,
                                std::optional<TristimulusMethod> method, E308Table e308_table) {
  const SpectrumPtr spectrum = make_emission_spectrum(source, library);
  return analyse_spectrum(*spectrum, source.describe(), library, method, e308_table);
}

SpectrumReport analyse_spectrum(const Spectrum& spectrum, const std::string& description, SpectralLibrary& library,
                                std::optional<TristimulusMethod> method, E308Table e308_table) {
  SpectrumReport r;
  r.description = description;
  const Observer& two = library.observer(StandardObserver::cie1931_2deg);
  const Observer& ten = library.observer(StandardObserver::cie1964_10deg);
  const auto* table = dynamic_cast<const TabulatedSpectrum*>(&spectrum);
  if (!table && method && *method != TristimulusMethod::interpolate_1nm)
    throw InputError({"", 0, "--method"}, "'" + description + "' is a continuous spectrum, not a table: only "
                                          "--method 1nm applies to it");
  const TristimulusMethod used =
      table ? method.value_or(default_tristimulus_method(*table)) : TristimulusMethod::interpolate_1nm;
  r.tristimulus_method = std::string(method_name(used));
  if (used == TristimulusMethod::astm_e308) r.e308_table = e308_table;
  if (table) {
    r.xyz_2deg = light_xyz(*table, StandardObserver::cie1931_2deg, used, library, e308_table);
    r.xyz_10deg = light_xyz(*table, StandardObserver::cie1964_10deg, used, library, e308_table);
  } else {
    r.xyz_2deg = illuminant_xyz(spectrum, two);
    r.xyz_10deg = illuminant_xyz(spectrum, ten);
  }
  r.xy_2deg = chromaticity_of(r.xyz_2deg);
  r.uv_prime_2deg = uv1976_of(r.xyz_2deg);
  r.xy_10deg = chromaticity_of(r.xyz_10deg);
  if (table && used == TristimulusMethod::native) {
    const double step_nm = *uniform_interval_nm(*table);
    const IntegrationGrid grid{std::max(table->wavelengths_nm().front(), kCmfFirst_nm),
                               std::min(table->wavelengths_nm().back(), kCmfLast_nm), step_nm};
    r.absolute_xyz = emission_xyz(spectrum, two, grid);
  } else {
    r.absolute_xyz = emission_xyz(spectrum, two);
  }
  r.cct = PlanckianLocus(two).cct_duv(uv1960_of(r.xyz_2deg));
  r.luminous_efficacy_lm_w = luminous_efficacy_of_radiation_lm_W(spectrum, library.photopic_v()).lm_W;
  r.scotopic_luminous_efficacy_lm_w = scotopic_luminous_efficacy_lm_W(spectrum, library.scotopic_v_prime()).lm_W;
  try {
    r.cri = ColourRenderingEvaluator(library).evaluate(spectrum);
  } catch (const InputError& e) {
    r.cri_unavailable_reason = e.explanation();
  }
  r.srgb_linear = colour_at_unit_luminance(r.xyz_2deg, RgbColourSpace::named("srgb-linear"));
  r.acescg = colour_at_unit_luminance(r.xyz_2deg, RgbColourSpace::named("acescg"));
  return r;
}

std::string report_text(const SpectrumReport& r) {
  std::ostringstream out;
  out << "spectrum           " << r.description << "\n";
  out << "tristimulus method " << r.tristimulus_method << "\n";
  if (r.e308_table) out << "e308 weights       " << e308_table_description(*r.e308_table) << "\n";
  out << format_numbers("XYZ (2°, Y=100)    %.4f %.4f %.4f\n", r.xyz_2deg.x, r.xyz_2deg.y, r.xyz_2deg.z);
  out << format_numbers("xy  (2°)           %.5f %.5f\n", r.xy_2deg.x, r.xy_2deg.y);
  out << format_numbers("u'v' (2°)          %.5f %.5f\n", r.uv_prime_2deg.u, r.uv_prime_2deg.v);
  out << format_numbers("XYZ (10°, Y=100)   %.4f %.4f %.4f\n", r.xyz_10deg.x, r.xyz_10deg.y, r.xyz_10deg.z);
  out << format_numbers("xy  (10°)          %.5f %.5f\n", r.xy_10deg.x, r.xy_10deg.y);
  out << format_numbers("CCT                %.1f K   Duv %.5f", r.cct.cct_k, r.cct.duv) << "   ("
      << cct_validity_name(r.cct.validity) << ")\n";
  out << format_numbers("luminous efficacy  %.2f lm/W photopic, %.2f lm/W scotopic (of radiation, 360-830 nm)\n",
                r.luminous_efficacy_lm_w, r.scotopic_luminous_efficacy_lm_w);
  out << format_numbers("absolute Y         %.6g (K_m·∫S·ȳ dλ: cd/m² if S is in W/(m²·sr·nm))\n", r.absolute_xyz.y);
  if (r.cri) {
    out << format_numbers("CRI Ra             %.1f", r.cri->ra)
        << (r.cri->duv_within_cie_limit ? "" : "   (|Duv| > 5.4e-3: CIE 13.3 calls this not meaningful)") << "\n";
    out << "CRI R1-R14        ";
    for (double ri : r.cri->special) out << format_numbers(" %.0f", ri);
    out << "\n";
  } else {
    out << "CRI                n/a: " << r.cri_unavailable_reason << "\n";
  }
  out << format_numbers("linear sRGB (Y=1)  %.5f %.5f %.5f\n", r.srgb_linear.r, r.srgb_linear.g, r.srgb_linear.b);
  out << format_numbers("ACEScg (Y=1)       %.5f %.5f %.5f\n", r.acescg.r, r.acescg.g, r.acescg.b);
  return out.str();
}

std::string report_json(const SpectrumReport& r) {
  nlohmann::ordered_json j;
  j["spectrum"] = r.description;
  add_tristimulus_method_json(j, r.tristimulus_method, r.e308_table);
  j["xyz_2deg"] = {r.xyz_2deg.x, r.xyz_2deg.y, r.xyz_2deg.z};
  j["xy_2deg"] = {r.xy_2deg.x, r.xy_2deg.y};
  j["uv_prime_2deg"] = {r.uv_prime_2deg.u, r.uv_prime_2deg.v};
  j["xyz_10deg"] = {r.xyz_10deg.x, r.xyz_10deg.y, r.xyz_10deg.z};
  j["xy_10deg"] = {r.xy_10deg.x, r.xy_10deg.y};
  j["absolute_y"] = r.absolute_xyz.y;
  j["cct_k"] = r.cct.cct_k;
  j["duv"] = r.cct.duv;
  j["cct_valid"] = r.cct.valid();
  j["luminous_efficacy_lm_w"] = r.luminous_efficacy_lm_w;
  j["scotopic_luminous_efficacy_lm_w"] = r.scotopic_luminous_efficacy_lm_w;
  if (r.cri) {
    j["cri_ra"] = r.cri->ra;
    j["cri_special"] = r.cri->special;
    j["cri_meaningful"] = r.cri->duv_within_cie_limit;
  } else {
    j["cri_ra"] = nullptr;
    j["cri_unavailable_reason"] = r.cri_unavailable_reason;
  }
  j["srgb_linear"] = {r.srgb_linear.r, r.srgb_linear.g, r.srgb_linear.b};
  j["acescg"] = {r.acescg.r, r.acescg.g, r.acescg.b};
  return j.dump(2) + "\n";
}

}  // namespace rimu
