#include "spectral/colorimetry/daylight.h"

#include <cmath>
#include <sstream>

#include "spectral/error.h"

namespace rimu {

Chromaticity daylight_chromaticity(double cct_k) {
  if (!(cct_k >= 4000.0 && cct_k <= 25000.0))
    throw InputError({}, "CIE daylight is defined for correlated colour temperatures 4000-25000 K, got " +
                             std::to_string(cct_k) + " K");
  const double t = 1.0 / cct_k;
  const double x = cct_k <= 7000.0 ? -4.6070e9 * t * t * t + 2.9678e6 * t * t + 0.09911e3 * t + 0.244063
                                   : -2.0064e9 * t * t * t + 1.9018e6 * t * t + 0.24748e3 * t + 0.237040;
  const double y = -3.000 * x * x + 2.870 * x - 0.275;
  return {x, y};
}

double cie_daylight_defined_cct_k(double nominal_k) { return nominal_k * 1.4388 / 1.4380; }

TabulatedSpectrum daylight_spectrum(const DaylightBasis& basis, double cct_k, DaylightRounding rounding) {
  const Chromaticity c = daylight_chromaticity(cct_k);
  const double m = 0.0241 + 0.2562 * c.x - 0.7341 * c.y;
  double m1 = (-1.3515 - 1.7703 * c.x + 5.9114 * c.y) / m;
  double m2 = (0.0300 - 31.4424 * c.x + 30.0717 * c.y) / m;
  if (rounding == DaylightRounding::cie_three_decimals) {
    m1 = std::round(m1 * 1000.0) / 1000.0;
    m2 = std::round(m2 * 1000.0) / 1000.0;
  }
  const auto& grid = basis.s0.wavelengths_nm();
  std::vector<double> values(grid.size());
  for (size_t i = 0; i < grid.size(); ++i)
    values[i] = basis.s0.values()[i] + m1 * basis.s1.value(grid[i]) + m2 * basis.s2.value(grid[i]);
  std::ostringstream name;
  name << "CIE daylight " << cct_k << " K";
  return TabulatedSpectrum(grid, std::move(values), Extrapolation::zero, name.str());
}

}  // namespace rimu
