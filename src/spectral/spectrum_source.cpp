#include "spectral/spectrum_source.h"

#include <cmath>
#include <sstream>

#include "spectral/blackbody_spectrum.h"
#include "spectral/colorimetry.h"
#include "spectral/csv_table.h"
#include "spectral/daylight.h"
#include "spectral/error.h"

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
  const std::vector<double> power = table.numbers(index);
  for (size_t r = 0; r < power.size(); ++r) {
    if (power[r] < 0.0)
      throw InputError({source.name, table.line_of_row(r), ""},
                       "column '" + column + "': spectral power cannot be negative, found " + table.cell(r, index));
  }
  return std::make_shared<TabulatedSpectrum>(TabulatedSpectrum::from_csv(table, column, Extrapolation::zero));
}

}  // namespace

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
    // A light with no power where any observer can see cannot be given a colour or a luminous intensity.
    const Observer& o = library.observer(StandardObserver::cie1931_2deg);
    const Xyz raw = emission_xyz(*spectrum, o);
    if (!(raw.x + raw.y + raw.z > 0.0))
      throw InputError({source.kind == SpectrumSource::Kind::csv_file ? source.name : "", 0, ""},
                       "the spectrum " + spectrum->describe() +
                           " has no power in 360-830 nm, so it has no colour or luminous value");
  } catch (const InputError& error) {
    rethrow_at(source.where, error);
  }
  return spectrum;
}

}  // namespace rimu
