#include "spectral/library/spectrum_source.h"

#include <cmath>
#include <sstream>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/daylight.h"
#include "spectral/error.h"
#include "spectral/spectra/spectrum_values_check.h"

namespace rimu {
namespace {

// Re-raises an error from a lower layer with the user's location in front, keeping file:line of the data file.
[[noreturn]] void rethrow_at(const SourceLocation& where, const InputError& error) {
  if (where.file.empty() && where.key.empty()) throw error;
  SourceLocation combined = error.where();
  if (combined.key.empty()) combined.key = where.key;
  if (combined.file.empty()) {
    combined.file = where.file;
    combined.line = where.line;
  }
  throw InputError(combined, error.explanation());
}

SpectrumPtr load_csv_emission(const SpectrumSource& source) {
  const CsvTable table = CsvTable::read(source.name);
  if (table.column_count() < 2)
    throw InputError({source.name, 1, ""}, "expected at least two columns: wavelength_nm and a spectral power");
  const std::string column = source.column.empty() ? table.header()[1] : source.column;
  const size_t index = table.column_index(column);
  check_spectral_power(table.numbers(index),
                       [&](size_t row) { return SourceLocation{source.name, table.line_of_row(row), column}; });
  return std::make_shared<TabulatedSpectrum>(TabulatedSpectrum::from_csv(table, column, Extrapolation::zero));
}

}  // namespace

void check_emission_spectrum(const Spectrum& spectrum, SpectralLibrary& library, const SourceLocation& where) {
  // A light with no power where any observer can see cannot be given a colour or a luminous intensity.
  const Observer& o = library.observer(StandardObserver::cie1931_2deg);
  const Xyz raw = emission_xyz(spectrum, o);
  // Relative colorimetry scales by 100 / Y: an integral that overflows, or whose reciprocal does, has no colour.
  const double sum = raw.x + raw.y + raw.z;
  if (!std::isfinite(sum))
    throw InputError(where, "the spectrum " + spectrum.describe() + " overflows: its integral over 360-830 nm is not "
                            "a finite number; give its values in a smaller unit");
  if (sum > 0.0 && !std::isfinite(1.0 / sum))
    throw InputError(where, "the spectrum " + spectrum.describe() + " is too faint to compute with: its integral over "
                            "360-830 nm is below 1e-308; give its values in a larger unit");
  if (!(sum > 0.0))
    throw InputError(where, "the spectrum " + spectrum.describe() +
                                " has no power in 360-830 nm, so it has no colour or luminous value");
}

std::string SpectrumSource::describe() const {
  std::ostringstream out;
  switch (kind) {
    case Kind::named_illuminant: out << "CIE " << name; break;
    case Kind::csv_file: out << name << (column.empty() ? "" : " [" + column + "]"); break;
    case Kind::blackbody: out << "blackbody " << number << " K"; break;
    case Kind::daylight: out << "CIE daylight " << number << " K"; break;
    case Kind::constant: out << "constant " << number; break;
  }
  return out.str();
}

SpectrumPtr make_emission_spectrum(const SpectrumSource& source, SpectralLibrary& library) {
  SpectrumPtr spectrum;
  try {
    switch (source.kind) {
      case SpectrumSource::Kind::named_illuminant: spectrum = library.illuminant(source.name); break;
      case SpectrumSource::Kind::csv_file: spectrum = load_csv_emission(source); break;
      case SpectrumSource::Kind::blackbody:
        spectrum = std::make_shared<BlackbodySpectrum>(source.number, BlackbodySpectrum::Scale::absolute_radiance);
        break;
      case SpectrumSource::Kind::daylight:
        spectrum = std::make_shared<TabulatedSpectrum>(daylight_spectrum(library.daylight_basis(), source.number));
        break;
      case SpectrumSource::Kind::constant:
        if (!(source.number >= 0.0) || !std::isfinite(source.number))
          throw InputError({}, "a constant spectral power must be a finite number >= 0");
        spectrum = std::make_shared<ConstantSpectrum>(source.number);
        break;
    }
    check_emission_spectrum(*spectrum, library,
                            {source.kind == SpectrumSource::Kind::csv_file ? source.name : "", 0, ""});
  } catch (const InputError& error) {
    rethrow_at(source.where, error);
  }
  return spectrum;
}

}  // namespace rimu
