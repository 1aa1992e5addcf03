// The checks on a spectrum's numbers as a user gives them: a CSV column for the tools, a scene list, the Python
// module's arrays. Every front end calls these, so each refuses the same things with the same explanation; the
// caller says where each sample came from (a file and line, or a Python argument and index).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "spectral/error.h"

namespace rimu {

/// Where sample `index` of the numbers being checked came from: `{file, line_of_row(index), column}` for a CSV,
/// `{"", 0, "values[3]"}` for an array argument.
using SampleLocation = std::function<SourceLocation(std::size_t index)>;

/// Wavelengths in nm: finite, strictly increasing, and ending at 100 nm or above (a table in micrometres, as optics
/// databases publish, would otherwise lie far below the visible range: a silently black or constant spectrum).
/// Throws InputError at the first offending sample.
void check_wavelengths_nm(const std::vector<double>& wavelengths_nm, const SampleLocation& where);

/// Spectral power (of a light): finite, never negative (a negative power has no physical meaning, and relative
/// colorimetry divides by Y, so an all-negative spectrum would silently give the colour of its opposite) and never
/// subnormal (0 < p < 2.2e-308: too small to compute with).
void check_spectral_power(const std::vector<double>& power, const SampleLocation& where);

/// A reflectance factor above this is refused: fluorescent samples reach ~1.3, anything higher is a file in
/// percent or a radiance by mistake.
inline constexpr double kMaxReflectanceFactor = 1.5;

/// Reflectance (or transmittance) factors: finite, in [0, kMaxReflectanceFactor].
void check_reflectance_factors(const std::vector<double>& factors, const SampleLocation& where);

}  // namespace rimu
