// The explicit context that owns Rimu's published spectral tables.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/csv_table.h"
#include "spectral/daylight.h"
#include "spectral/observer.h"
#include "spectral/spectrum.h"

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
  const DaylightBasis& daylight_basis();

  /// A CIE illuminant by name: A, D50, D65, E, F1-F12, FL3.1-FL3.15, HP1-HP5, LED-B1...LED-V2 (relative power).
  /// Throws InputError listing the known names.
  SpectrumPtr illuminant(std::string_view name);
  static std::vector<std::string> illuminant_names();

  /// A reflectance of the ColorChecker Classic (BabelColor average, 10 nm) by column name, e.g. "dark_skin".
  SpectrumPtr colorchecker_patch(std::string_view name);
  /// The 24 patch names in chart order.
  std::vector<std::string> colorchecker_patch_names();

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
  std::unique_ptr<TabulatedSpectrum> photopic_v_, scotopic_v_prime_;
  std::unique_ptr<DaylightBasis> daylight_basis_;
};

}  // namespace rimu
