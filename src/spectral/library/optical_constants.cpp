#include "spectral/library/optical_constants.h"

#include <algorithm>
#include <cmath>

#include "spectral/io/csv_table.h"
#include "spectral/error.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {
namespace {

constexpr std::string_view kGlassFile = "spectra/materials/sellmeier_glasses.csv";
constexpr std::string_view kWaterFile = "spectra/materials/sellmeier_water_daimon2007_20C.csv";

struct DielectricSource {
  std::string_view name;
  std::string_view file;
  std::string_view row;  // value of the "material" column in kGlassFile; empty for the water file
};

// SCHOTT catalogue (N-BK7, N-SF11), Malitson 1965 (fused silica), Daimon & Masumura 2007 (water, 20 °C);
// provenance in data/spectra/README.md.
constexpr DielectricSource kDielectrics[] = {
    {"bk7", kGlassFile, "Schott N-BK7"},
    {"sf11", kGlassFile, "Schott N-SF11"},
    {"fused-silica", kGlassFile, "Fused silica (Malitson 1965)"},
    {"water", kWaterFile, ""},
};

struct ConductorSource {
  std::string_view name;
  std::string_view file;
};

// Gold, silver, copper: Johnson & Christy 1972, the standard measurement for the noble metals (thin films,
// 0.5-6.5 eV), and the only tables we ship for them. Aluminium: McPeak et al. 2015 rather than Rakić 1995,
// because McPeak's table is measured on a modern ultrasmooth evaporated film on a regular 5 nm grid, so linear
// interpolation resolves the interband absorption near 800 nm, whereas Rakić's is a Lorentz-Drude model fit
// listed at only 21 irregular wavelengths.
constexpr ConductorSource kConductors[] = {
    {"gold", "spectra/materials/au_nk_johnson_christy_1972.csv"},
    {"silver", "spectra/materials/ag_nk_johnson_christy_1972.csv"},
    {"copper", "spectra/materials/cu_nk_johnson_christy_1972.csv"},
    {"aluminium", "spectra/materials/al_nk_mcpeak_2015.csv"},
    // pbrt-v4's own tables (its metal-*-eta/-k named spectra), so that imported pbrt scenes reproduce pbrt; pbrt
    // names no source for them (data/spectra/README.md).
    {"pbrt-au", "spectra/materials/pbrt_metal_au_nk.csv"},
    {"pbrt-ag", "spectra/materials/pbrt_metal_ag_nk.csv"},
    {"pbrt-cu", "spectra/materials/pbrt_metal_cu_nk.csv"},
    {"pbrt-al", "spectra/materials/pbrt_metal_al_nk.csv"},
    {"pbrt-cuzn", "spectra/materials/pbrt_metal_cuzn_nk.csv"},
    {"pbrt-mgo", "spectra/materials/pbrt_metal_mgo_nk.csv"},
    {"pbrt-tio2", "spectra/materials/pbrt_metal_tio2_nk.csv"},
};

// pbrt-v4's glass-* named spectra: refractiveindex.info's SCHOTT formulas as pbrt tabulated them (~22 nm steps),
// read as tables (linear between points, end values beyond) so that imported pbrt scenes disperse as in pbrt.
struct TabulatedDielectricSource {
  std::string_view name;
  std::string_view file;
};
constexpr TabulatedDielectricSource kTabulatedDielectrics[] = {
    {"pbrt-bk7", "spectra/materials/pbrt_glass_bk7_n.csv"},     {"pbrt-baf10", "spectra/materials/pbrt_glass_baf10_n.csv"},
    {"pbrt-fk51a", "spectra/materials/pbrt_glass_fk51a_n.csv"}, {"pbrt-lasf9", "spectra/materials/pbrt_glass_lasf9_n.csv"},
    {"pbrt-sf5", "spectra/materials/pbrt_glass_sf5_n.csv"},     {"pbrt-sf10", "spectra/materials/pbrt_glass_sf10_n.csv"},
    {"pbrt-sf11", "spectra/materials/pbrt_glass_sf11_n.csv"},
};

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

double number_cell(const CsvTable& table, size_t row, size_t column) {
  double v = 0;
  if (!parse_finite_number(table.cell(row, column), v))
    throw InputError({table.name(), table.line_of_row(row), table.header()[column]},
                     "expected a finite number, found '" + table.cell(row, column) + "'");
  return v;
}

std::vector<SellmeierTerm> glass_terms(const CsvTable& table, std::string_view row_name) {
  const size_t material = table.column_index("material");
  for (size_t r = 0; r < table.row_count(); ++r) {
    if (table.cell(r, material) != row_name) continue;
    std::vector<SellmeierTerm> terms;
    for (int i = 1; i <= 3; ++i) {
      const std::string index = std::to_string(i);
      terms.push_back({number_cell(table, r, table.column_index("B" + index)),
                       number_cell(table, r, table.column_index("C" + index + "_um2"))});
    }
    return terms;
  }
  throw InputError({table.name(), 0, ""}, "no row for '" + std::string(row_name) + "' in the material column");
}

std::vector<SellmeierTerm> water_terms(const CsvTable& table) {
  const size_t b = table.column_index("B"), c = table.column_index("C_um2");
  std::vector<SellmeierTerm> terms;
  for (size_t r = 0; r < table.row_count(); ++r) terms.push_back({number_cell(table, r, b), number_cell(table, r, c)});
  return terms;
}

}  // namespace

SellmeierSpectrum::SellmeierSpectrum(std::vector<SellmeierTerm> terms, std::string name) : name_(std::move(name)) {
  if (terms.empty() || terms.size() > size_t(kMaxTerms))
    throw InputError({name_, 0, ""}, "a Sellmeier formula needs 1 to 4 terms, got " + std::to_string(terms.size()));
  const double lo_um2 = (kLambdaMinNm * 1e-3) * (kLambdaMinNm * 1e-3);
  const double hi_um2 = (kLambdaMaxNm * 1e-3) * (kLambdaMaxNm * 1e-3);
  for (size_t i = 0; i < terms.size(); ++i) {
    // A pole (λ² = C) inside the transported range would give an infinite or imaginary index there.
    if (terms[i].c_um2 >= lo_um2 && terms[i].c_um2 <= hi_um2)
      throw InputError({name_, 0, ""}, "Sellmeier term " + std::to_string(i + 1) + " has its pole inside 360-830 nm");
    terms_[i] = terms[i];
  }
  for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 1.0) max_value_ = std::max(max_value_, value(l));
}

double SellmeierSpectrum::value(double lambda_nm) const {
  const double l2 = (lambda_nm * 1e-3) * (lambda_nm * 1e-3);
  double n2_minus_1 = 0;
  for (const auto& t : terms_) n2_minus_1 += t.b * l2 / (l2 - t.c_um2);
  return std::sqrt(std::max(0.0, 1.0 + n2_minus_1));
}

SampledSpectrum SellmeierSpectrum::sample(const SampledWavelengths& lambda) const {
  const Float4 l_um = lambda.lambda_nm() * Float4(1e-3f);
  const Float4 l2 = l_um * l_um;
  Float4 n2 = Float4(1.0f);
  for (const auto& t : terms_) n2 += Float4(float(t.b)) * l2 / (l2 - Float4(float(t.c_um2)));
  return sqrt(max(n2, Float4(0.0f)));
}

std::vector<std::string> dielectric_names() {
  std::vector<std::string> names;
  for (const auto& d : kDielectrics) names.emplace_back(d.name);
  for (const auto& d : kTabulatedDielectrics) names.emplace_back(d.name);
  return names;
}

SpectrumPtr dielectric_ior(SpectralLibrary& library, std::string_view name) {
  for (const auto& d : kDielectrics) {
    if (d.name != name) continue;
    const CsvTable& table = library.table(std::string(d.file));
    auto terms = d.row.empty() ? water_terms(table) : glass_terms(table, d.row);
    const std::string label = std::string(d.name) + " (Sellmeier, " + table.name() + ")";
    return std::make_shared<SellmeierSpectrum>(std::move(terms), label);
  }
  for (const auto& d : kTabulatedDielectrics) {
    if (d.name != name) continue;
    const CsvTable& table = library.table(std::string(d.file));
    auto n = std::make_shared<TabulatedSpectrum>(TabulatedSpectrum::from_csv(table, "n", Extrapolation::clamp));
    if (n->min_value() <= 0.0) throw InputError({table.name(), 0, ""}, "an index of refraction must be > 0 at every wavelength");
    return n;
  }
  throw InputError({}, "unknown dielectric '" + std::string(name) + "'; known dielectrics: " + join(dielectric_names()));
}

std::vector<std::string> conductor_names() {
  std::vector<std::string> names;
  for (const auto& c : kConductors) names.emplace_back(c.name);
  return names;
}

ComplexIorSpectra conductor_ior(SpectralLibrary& library, std::string_view name) {
  for (const auto& c : kConductors) {
    if (c.name != name) continue;
    const CsvTable& table = library.table(std::string(c.file));
    // Every shipped table covers 360-830 nm (Johnson & Christy 284-984 nm, McPeak 280-1000 nm); clamping at the
    // ends (CIE 15:2004 §7.2.2.1's nearest-value rule) only matters for tables that stop short.
    auto n = std::make_shared<TabulatedSpectrum>(TabulatedSpectrum::from_csv(table, "n", Extrapolation::clamp));
    auto k = std::make_shared<TabulatedSpectrum>(TabulatedSpectrum::from_csv(table, "k", Extrapolation::clamp));
    if (n->min_value() <= 0.0 || k->min_value() < 0.0)
      throw InputError({table.name(), 0, ""}, "a conductor needs n > 0 and k >= 0 at every wavelength");
    return {n, k};
  }
  throw InputError({}, "unknown conductor '" + std::string(name) + "'; known conductors: " + join(conductor_names()));
}

}  // namespace rimu
