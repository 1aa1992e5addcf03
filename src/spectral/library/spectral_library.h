// The explicit context that owns Rimu's published spectral tables.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/colorimetry/astm_e308.h"
#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/daylight.h"
#include "spectral/colorimetry/observer.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

enum class StandardObserver {
  cie1931_2deg,   ///< CIE 1931 2° (CIE 15:2004 Table T.4)
  cie1964_10deg,  ///< CIE 1964 10° (CIE 15:2004 Table T.5)
};

/// Loads observers, illuminants, reflectances and other tables from a data folder, on first use, and keeps them.
///
/// There is no global instance: whoever needs tables builds (or is handed) one, so a test loads exactly what it
/// uses. Loading is guarded by a mutex, but it is meant to happen at setup (scene load, CLI start), never in the
/// per-sample loop. Every missing or malformed file is an InputError naming the file and line.
class SpectralLibrary {
 public:
  explicit SpectralLibrary(std::filesystem::path data_root);
  /// A library on find_data_directory().
  static SpectralLibrary at_default_location();

  const std::filesystem::path& root() const { return root_; }

  const Observer& observer(StandardObserver which);
  /// CIE 1924 photopic V(λ) (= ȳ of 1931 2°), peak 1 at 555 nm.
  const TabulatedSpectrum& photopic_v();
  /// CIE 1951 scotopic V'(λ), peak 1 at 507 nm.
  const TabulatedSpectrum& scotopic_v_prime();
  /// CIE S 026/E:2018 melanopic action spectrum s_mel(λ), peak 1 at 490 nm, 380-780 nm (0 outside).
  const TabulatedSpectrum& melanopic_action_spectrum();
  const DaylightBasis& daylight_basis();

  /// A CIE illuminant by name: A, D50, D55, D65, D75, E, F1-F12, FL3.1-FL3.15, HP1-HP5, LED-B1...LED-V2 (relative
  /// power). D55 and D75 have no table in data/: they are computed as CIE 15:2004 §3.1 defines them, from the
  /// S0, S1, S2 basis at 5503 K and 7504 K with M1, M2 rounded to 3 decimals, linear between the basis' 5 nm
  /// values (which is how the CIE's own 1 nm D50 and D65 tables are made). Throws InputError listing the known names.
  SpectrumPtr illuminant(std::string_view name);
  static std::vector<std::string> illuminant_names();

  /// A reflectance of the ColorChecker Classic (BabelColor average, 10 nm) by column name, e.g. "dark_skin".
  SpectrumPtr colorchecker_patch(std::string_view name);
  /// The 24 patch names in chart order.
  std::vector<std::string> colorchecker_patch_names();

  /// ASTM E308 weighting factors for data every `interval_nm` (10 or 20) under a CIE illuminant (A, C, D50, D55,
  /// D65, D75, E, F2, F7, F11: the illuminants of E308-15 Tables 5 and 6, plus E), read from data/e308/ (generated
  /// by tools/rimu-e308-weights). Throws InputError naming the
  /// illuminants and intervals that have tables.
  /// `table`: Table 6 (data corrected for bandpass, astm_e308_<name>_<2|10>deg_<10|20>nm.csv) or Table 5
  /// (uncorrected data, the same name ending _table5.csv).
  const E308WeightTable& e308_weights(std::string_view illuminant, StandardObserver observer, double interval_nm,
                                      E308Table table = E308Table::table6_bandpass_corrected);
  /// The illuminants data/e308/ holds weights for.
  static std::vector<std::string> e308_illuminant_names();
  /// The 1 nm spectrum the E308 weights of `name` are computed from. A, D65: the CIE 1 nm tables; E: a
  /// constant. D50: the CIE 5 nm table; C: CIE 15:2004 Table T.1 (5 nm, held beyond 780 nm); D55, D75, F2, F7,
  /// F11: illuminant(name) on its 5 nm grid (the daylight basis' S0 + M1 S1 + M2 S2; CIE 15:2004 Table T.6 for
  /// F); all taken to 1 nm by e308_interpolate_to_1nm(), the E2022 Lagrange polynomials.
  /// That is what reproduces E308's published white points (D55, F2, F11 to their 3 decimals, D75, F7 within 6.1e-4):
  /// linear interpolation misses Z by 0.011 (D55) and 0.019 (D75), and the CIE 15:2018 1 nm FL table
  /// (cie_fl_1nm.csv, mercury lines at their real wavelengths; published after E308-15) by up to 0.002.
  SpectrumPtr e308_illuminant(std::string_view name);

  /// A CSV file read through the cache (path relative to the data root, or absolute).
  const CsvTable& table(const std::filesystem::path& path);

 private:
  std::filesystem::path resolve(const std::filesystem::path& path) const;
  const CsvTable& table_unlocked(const std::filesystem::path& path);

  std::filesystem::path root_;
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<CsvTable>> tables_;
  std::map<StandardObserver, std::unique_ptr<Observer>> observers_;
  std::map<std::string, SpectrumPtr, std::less<>> spectra_;
  std::map<std::string, std::unique_ptr<E308WeightTable>> e308_tables_;
  std::unique_ptr<TabulatedSpectrum> photopic_v_, scotopic_v_prime_, melanopic_;
  std::unique_ptr<DaylightBasis> daylight_basis_;
};

}  // namespace rimu
