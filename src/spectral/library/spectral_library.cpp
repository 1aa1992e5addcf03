#include "spectral/library/spectral_library.h"

#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "spectral/io/csv_table.h"
#include "spectral/io/data_directory.h"
#include "spectral/error.h"

namespace rimu {
namespace {

struct IlluminantSource {
  std::string_view file;
  std::vector<std::string> columns;
};

// Which table holds which illuminant. A, D50 and D65 come from the 1 nm CIE tables; the others from CIE 15's
// 5 nm tabulations (the data the CIE publishes their chromaticities and CRI from).
const std::vector<IlluminantSource>& illuminant_sources() {
  static const std::vector<IlluminantSource> sources = [] {
    std::vector<IlluminantSource> s = {
        {"spectra/illuminants/cie_a_1nm.csv", {"A"}},
        {"spectra/illuminants/cie_d50_1nm.csv", {"D50"}},
        {"spectra/illuminants/cie_d65_1nm.csv", {"D65"}},
        {"spectra/illuminants/cie_e_5nm.csv", {"E"}},
        {"spectra/illuminants/cie_f1_f12_5nm.csv", {}},
        {"spectra/illuminants/cie_fl3_1_15_5nm.csv", {}},
        {"spectra/illuminants/cie_hp1_hp5_5nm.csv", {"HP1", "HP2", "HP3", "HP4", "HP5"}},
        {"spectra/illuminants/cie_led_5nm.csv",
         {"LED-B1", "LED-B2", "LED-B3", "LED-B4", "LED-B5", "LED-BH1", "LED-RGB1", "LED-V1", "LED-V2"}},
        {"spectra/illuminants/cie_c_5nm.csv", {"C"}},
    };
    for (int i = 1; i <= 12; ++i) s[4].columns.push_back("F" + std::to_string(i));
    for (int i = 1; i <= 15; ++i) s[5].columns.push_back("FL3." + std::to_string(i));
    return s;
  }();
  return sources;
}

// The D illuminants CIE 15 defines but publishes no table of here: name and nominal temperature (K).
struct ComputedDaylight {
  std::string_view name;
  double nominal_k;
};
constexpr ComputedDaylight kComputedDaylights[] = {{"D55", 5500.0}, {"D75", 7500.0}};

constexpr std::string_view kColorChecker = "spectra/reflectances/colorchecker_classic_babelcolor_avg_10nm.csv";

}  // namespace

SpectralLibrary::SpectralLibrary(std::filesystem::path data_root) : root_(std::move(data_root)) {}

SpectralLibrary SpectralLibrary::at_default_location() { return SpectralLibrary(find_data_directory()); }

std::filesystem::path SpectralLibrary::resolve(const std::filesystem::path& path) const {
  return path.is_absolute() ? path : root_ / path;
}

const CsvTable& SpectralLibrary::table(const std::filesystem::path& path) {
  std::lock_guard lock(mutex_);
  return table_unlocked(path);
}

const CsvTable& SpectralLibrary::table_unlocked(const std::filesystem::path& path) {
  const std::string key = resolve(path).string();
  auto it = tables_.find(key);
  if (it == tables_.end()) it = tables_.emplace(key, std::make_unique<CsvTable>(CsvTable::read(key))).first;
  return *it->second;
}

const Observer& SpectralLibrary::observer(StandardObserver which) {
  std::lock_guard lock(mutex_);
  auto& slot = observers_[which];
  if (!slot) {
    const bool ten = which == StandardObserver::cie1964_10deg;
    const CsvTable& t = table_unlocked(ten ? "cmf/cie1964_10deg_xyz_1nm.csv" : "cmf/cie1931_2deg_xyz_1nm.csv");
    const std::string suffix = ten ? "10" : "";
    // The CMFs are tabulated over the whole 360-830 nm range; zero outside it.
    slot = std::make_unique<Observer>(Observer{
        ten ? "CIE 1964 10°" : "CIE 1931 2°",
        TabulatedSpectrum::from_csv(t, "xbar" + suffix, Extrapolation::zero),
        TabulatedSpectrum::from_csv(t, "ybar" + suffix, Extrapolation::zero),
        TabulatedSpectrum::from_csv(t, "zbar" + suffix, Extrapolation::zero)});
  }
  return *slot;
}

const TabulatedSpectrum& SpectralLibrary::photopic_v() {
  std::lock_guard lock(mutex_);
  if (!photopic_v_)
    photopic_v_ = std::make_unique<TabulatedSpectrum>(
        TabulatedSpectrum::from_csv(table_unlocked("cmf/cie1924_photopic_v_1nm.csv"), "V", Extrapolation::zero));
  return *photopic_v_;
}

const TabulatedSpectrum& SpectralLibrary::scotopic_v_prime() {
  std::lock_guard lock(mutex_);
  if (!scotopic_v_prime_)
    scotopic_v_prime_ = std::make_unique<TabulatedSpectrum>(
        TabulatedSpectrum::from_csv(table_unlocked("cmf/cie1951_scotopic_vprime_1nm.csv"), "Vprime", Extrapolation::zero));
  return *scotopic_v_prime_;
}

const TabulatedSpectrum& SpectralLibrary::melanopic_action_spectrum() {
  std::lock_guard lock(mutex_);
  if (!melanopic_)
    melanopic_ = std::make_unique<TabulatedSpectrum>(
        TabulatedSpectrum::from_csv(table_unlocked("cmf/cie_s026_melanopic_1nm.csv"), "smel", Extrapolation::zero));
  return *melanopic_;
}

const DaylightBasis& SpectralLibrary::daylight_basis() {
  std::lock_guard lock(mutex_);
  if (!daylight_basis_) {
    const CsvTable& t = table_unlocked("spectra/illuminants/cie_d_series_basis_s0_s1_s2_5nm.csv");
    daylight_basis_ = std::make_unique<DaylightBasis>(DaylightBasis{
        TabulatedSpectrum::from_csv(t, "S0", Extrapolation::zero),
        TabulatedSpectrum::from_csv(t, "S1", Extrapolation::zero),
        TabulatedSpectrum::from_csv(t, "S2", Extrapolation::zero)});
  }
  return *daylight_basis_;
}

std::vector<std::string> SpectralLibrary::illuminant_names() {
  std::vector<std::string> names;
  for (const auto& source : illuminant_sources())
    for (const auto& c : source.columns) names.push_back(c);
  for (const auto& d : kComputedDaylights) names.emplace_back(d.name);
  return names;
}

SpectrumPtr SpectralLibrary::illuminant(std::string_view name) {
  std::lock_guard lock(mutex_);
  const std::string key = "illuminant:" + std::string(name);
  if (auto it = spectra_.find(key); it != spectra_.end()) return it->second;
  for (const auto& source : illuminant_sources()) {
    for (const auto& column : source.columns) {
      if (column != name) continue;
      auto s = std::make_shared<TabulatedSpectrum>(
          TabulatedSpectrum::from_csv(table_unlocked(source.file), column, Extrapolation::zero));
      spectra_.emplace(key, s);
      return s;
    }
  }
  for (const auto& d : kComputedDaylights) {
    if (d.name != name) continue;
    const CsvTable& t = table_unlocked("spectra/illuminants/cie_d_series_basis_s0_s1_s2_5nm.csv");
    const DaylightBasis basis{TabulatedSpectrum::from_csv(t, "S0", Extrapolation::zero),
                              TabulatedSpectrum::from_csv(t, "S1", Extrapolation::zero),
                              TabulatedSpectrum::from_csv(t, "S2", Extrapolation::zero)};
    const double cct_k = cie_daylight_defined_cct_k(d.nominal_k);
    const TabulatedSpectrum computed = daylight_spectrum(basis, cct_k, DaylightRounding::cie_three_decimals);
    char description[96];
    std::snprintf(description, sizeof description, "CIE %s (S0, S1, S2 at %.0f K, CIE 15:2004)",
                  std::string(d.name).c_str(), cct_k);
    auto s = std::make_shared<TabulatedSpectrum>(computed.wavelengths_nm(), computed.values(), Extrapolation::zero,
                                                 description);
    spectra_.emplace(key, s);
    return s;
  }
  std::string known;
  for (const auto& n : illuminant_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError({}, "unknown illuminant '" + std::string(name) + "'; known illuminants: " + known);
}

std::vector<std::string> SpectralLibrary::colorchecker_patch_names() {
  std::lock_guard lock(mutex_);
  const auto& header = table_unlocked(kColorChecker).header();
  return {header.begin() + 1, header.end()};
}

SpectrumPtr SpectralLibrary::colorchecker_patch(std::string_view name) {
  std::lock_guard lock(mutex_);
  const std::string key = "colorchecker:" + std::string(name);
  if (auto it = spectra_.find(key); it != spectra_.end()) return it->second;
  auto s = std::make_shared<TabulatedSpectrum>(
      TabulatedSpectrum::from_csv(table_unlocked(kColorChecker), std::string(name), Extrapolation::clamp));
  spectra_.emplace(key, s);
  return s;
}

std::vector<std::string> SpectralLibrary::e308_illuminant_names() {
  return {"A", "C", "D50", "D55", "D65", "D75", "E", "F2", "F7", "F11"};
}

SpectrumPtr SpectralLibrary::e308_illuminant(std::string_view name) {
  if (name == "D50") {
    // The CIE 5 nm D50 table taken to 1 nm, not the CIE 1 nm table: only the former gives E308's white points
    // (2°: 96.422, 82.5218 vs published 96.422, 82.521; the 1 nm table gives 96.4241, 82.5128).
    const CsvTable& t = table("spectra/illuminants/cie_d50_5nm.csv");
    return std::make_shared<TabulatedSpectrum>(
        e308_interpolate_to_1nm(TabulatedSpectrum::from_csv(t, "D50", Extrapolation::zero)));
  }
  if (name == "C") {
    // CIE 15 tabulates C only to 780 nm; E308's range runs to 830 nm: hold the 780 nm value (CIE 15:2004
    // §7.2.2.1's rule for missing end data; it moves X by 2e-4, well inside the published rounding).
    const auto five_nm = std::dynamic_pointer_cast<const TabulatedSpectrum>(illuminant(name));
    assert(five_nm);
    const TabulatedSpectrum one_nm = e308_interpolate_to_1nm(*five_nm);
    return std::make_shared<TabulatedSpectrum>(one_nm.wavelengths_nm(), one_nm.values(), Extrapolation::clamp,
                                               one_nm.describe());
  }
  if (name != "D55" && name != "D75" && name != "F2" && name != "F7" && name != "F11") return illuminant(name);
  // illuminant() holds these on their 5 nm grid (CIE 15's tables, or the daylight basis'); E308 takes them to
  // 1 nm by Lagrange interpolation.
  const auto five_nm = std::dynamic_pointer_cast<const TabulatedSpectrum>(illuminant(name));
  assert(five_nm);
  return std::make_shared<TabulatedSpectrum>(e308_interpolate_to_1nm(*five_nm));
}

const E308WeightTable& SpectralLibrary::e308_weights(std::string_view illuminant, StandardObserver observer,
                                                     double interval_nm, E308Table e308_table) {
  const bool ten = observer == StandardObserver::cie1964_10deg;
  const int interval = int(std::lround(interval_nm));
  bool known = false;
  for (const auto& n : e308_illuminant_names()) known = known || n == illuminant;
  if (!known || (interval != 10 && interval != 20) || std::abs(interval - interval_nm) > 1e-6) {
    std::string names;
    for (const auto& n : e308_illuminant_names()) names += (names.empty() ? "" : ", ") + n;
    char step[32];
    std::snprintf(step, sizeof step, "%g", interval_nm);
    throw InputError({}, "no ASTM E308 weights for illuminant '" + std::string(illuminant) + "' at " + step +
                             " nm; weights exist for " + names + " at 10 and 20 nm (2° and 10°); use the native "
                             "or 1nm tristimulus method");
  }
  std::string lower(illuminant);
  for (char& ch : lower) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  const std::string file = "e308/astm_e308_" + lower + "_" + (ten ? "10" : "2") + "deg_" +
                           std::to_string(interval) + "nm" +
                           (e308_table == E308Table::table5_uncorrected ? "_table5" : "") + ".csv";
  std::lock_guard lock(mutex_);
  auto& slot = e308_tables_[file];
  if (!slot) {
    const std::string observer_name = ten ? "CIE 1964 10°" : "CIE 1931 2°";
    slot = std::make_unique<E308WeightTable>(
        e308_weights_from_csv(table_unlocked(file), std::string(illuminant), observer_name));
  }
  return *slot;
}

}  // namespace rimu
