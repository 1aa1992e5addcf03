#include "spectral/spectra/spectrum_values_check.h"

#include "spectral/spectra/spectral_value_range.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace rimu {
namespace {

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

void check_finite(const std::vector<double>& values, const SampleLocation& where, const char* what) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) throw InputError(where(i), std::string(what) + " " + number(values[i]) + " is not a finite number");
}

}  // namespace

void check_wavelengths_nm(const std::vector<double>& nm, const SampleLocation& where) {
  check_finite(nm, where, "wavelength");
  for (std::size_t i = 1; i < nm.size(); ++i)
    if (!(nm[i] > nm[i - 1]))
      throw InputError(where(i), "wavelengths must increase strictly; found " + number(nm[i]) + " nm after " +
                                     number(nm[i - 1]) + " nm");
  if (!nm.empty() && nm.back() < 100.0)
    throw InputError(where(nm.size() - 1), "the wavelengths end at " + number(nm.back()) +
                                               ", below 100 nm: are they in micrometres? expected nanometres");
}

void check_spectral_power(const std::vector<double>& power, const SampleLocation& where) {
  check_finite(power, where, "spectral power");
  for (std::size_t i = 0; i < power.size(); ++i)
    if (power[i] < 0.0) throw InputError(where(i), "spectral power cannot be negative, found " + number(power[i]));
  // The range every front end accepts (spectral_value_range.h), the tools' CSV columns and these arrays alike. It
  // refuses subnormal powers too (0 < p < DBL_MIN has lost its precision, and relative colorimetry's 100 / Y of such
  // a spectrum overflows: NaN chromaticity and fidelity).
  for (std::size_t i = 0; i < power.size(); ++i)
    if (const std::string why = spectral_value_range_error(power[i]); !why.empty())
      throw InputError(where(i), "spectral power: " + why);
}

void check_reflectance_factors(const std::vector<double>& factors, const SampleLocation& where) {
  check_finite(factors, where, "reflectance factor");
  for (std::size_t i = 0; i < factors.size(); ++i) {
    if (factors[i] > kMaxReflectanceFactor)
      throw InputError(where(i), "reflectance factor " + number(factors[i]) + " is above " +
                                     number(kMaxReflectanceFactor) + ": expected a factor in 0-1 (in percent?)");
    if (factors[i] < 0.0)
      throw InputError(where(i), "reflectance factor " + number(factors[i]) + " is negative: expected a factor in 0-1");
  }
}

}  // namespace rimu
