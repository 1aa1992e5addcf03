// Tabulated spectra brought onto other wavelengths: a regular grid, a given sampling, or the union of two
// samplings for arithmetic between spectra (the Python module's Spectrum type is built on these).
#pragma once

#include <functional>
#include <vector>

#include "spectral/error.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

/// start, start + interval, ... up to end (included when it lies on the grid, within 1e-9 nm). Throws InputError at
/// `where` unless 0 < interval <= end - start and the grid has at most 1e6 points.
std::vector<double> regular_wavelength_grid(double start_nm, double end_nm, double interval_nm,
                                            const SourceLocation& where);

/// `spectrum` evaluated at `wavelengths_nm` (its own linear interpolation and extrapolation rule): a new table
/// with the same rule, named after the original.
TabulatedSpectrum resampled(const TabulatedSpectrum& spectrum, std::vector<double> wavelengths_nm);

/// op(a(λ), b(λ)) at every wavelength of either table (the union of their samplings, so neither loses a knot),
/// with `extrapolation` for the result.
TabulatedSpectrum combined(const TabulatedSpectrum& a, const TabulatedSpectrum& b,
                           const std::function<double(double, double)>& op, Extrapolation extrapolation,
                           std::string name);

}  // namespace rimu
