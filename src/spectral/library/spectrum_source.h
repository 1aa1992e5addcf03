// How a user names a spectrum: a CIE table, a CSV file, a blackbody, a daylight CCT or a constant.
#pragma once

#include <string>

#include "spectral/error.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

/// A user's description of a spectrum, as it comes from a CLI flag or a scene key.
struct SpectrumSource {
  enum class Kind { named_illuminant, csv_file, blackbody, daylight, constant };
  Kind kind = Kind::named_illuminant;
  std::string name;    ///< illuminant name (named_illuminant) or file path (csv_file)
  std::string column;  ///< csv_file: the value column; empty = the second column
  double number = 0;   ///< blackbody: temperature in K; daylight: CCT in K; constant: the value
  SourceLocation where;  ///< where the description came from, for errors

  /// "CIE D65", "blackbody 2856 K", "file.csv [power]", ...
  std::string describe() const;
};

/// Builds an emission spectrum (relative or absolute spectral power) from its description.
/// Throws InputError, prefixed with `source.where`, for: an unknown name, a missing or malformed file
/// (with its line), non-monotonic wavelengths, a negative or non-finite power, a temperature outside
/// (0, 1e6] K, a daylight CCT outside 4000-25000 K, or a spectrum with no power in 360-830 nm.
SpectrumPtr make_emission_spectrum(const SpectrumSource& source, SpectralLibrary& library);

/// The checks every emission spectrum passes once built, whatever front end built it (make_emission_spectrum, the
/// Python module's arrays): it has power in 360-830 nm, and its integrals there are finite numbers whose reciprocals
/// are finite too (relative colorimetry divides by them). Throws InputError at `where`.
void check_emission_spectrum(const Spectrum& spectrum, SpectralLibrary& library, const SourceLocation& where);

}  // namespace rimu
