#include "spectral/spectra/spectrum_resampling.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rimu {

std::vector<double> regular_wavelength_grid(double start_nm, double end_nm, double interval_nm,
                                            const SourceLocation& where) {
  if (!(interval_nm > 0.0) || !std::isfinite(interval_nm) || !(end_nm - start_nm >= interval_nm))
    throw InputError(where, "expected an interval in (0, " + std::to_string(end_nm - start_nm) +
                                "] nm (the spectrum's range), got " + std::to_string(interval_nm));
  const double steps = std::floor((end_nm - start_nm) / interval_nm + 1e-9);
  if (steps >= 1e6) throw InputError(where, "the interval gives more than 1e6 wavelengths");
  std::vector<double> grid(size_t(steps) + 1);
  // Each point from the start (not by accumulation), so the grid has no drift.
  for (size_t i = 0; i < grid.size(); ++i) grid[i] = start_nm + double(i) * interval_nm;
  return grid;
}

TabulatedSpectrum resampled(const TabulatedSpectrum& spectrum, std::vector<double> wavelengths_nm) {
  std::vector<double> values(wavelengths_nm.size());
  std::transform(wavelengths_nm.begin(), wavelengths_nm.end(), values.begin(),
                 [&](double l) { return spectrum.value(l); });
  return TabulatedSpectrum(std::move(wavelengths_nm), std::move(values), spectrum.extrapolation(),
                           spectrum.describe());
}

TabulatedSpectrum combined(const TabulatedSpectrum& a, const TabulatedSpectrum& b,
                           const std::function<double(double, double)>& op, Extrapolation extrapolation,
                           std::string name) {
  std::vector<double> grid;
  std::set_union(a.wavelengths_nm().begin(), a.wavelengths_nm().end(), b.wavelengths_nm().begin(),
                 b.wavelengths_nm().end(), std::back_inserter(grid));
  std::vector<double> values(grid.size());
  std::transform(grid.begin(), grid.end(), values.begin(), [&](double l) { return op(a.value(l), b.value(l)); });
  return TabulatedSpectrum(std::move(grid), std::move(values), extrapolation, std::move(name));
}

}  // namespace rimu
