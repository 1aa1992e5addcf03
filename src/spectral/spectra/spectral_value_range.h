// The range of spectral values Rimu accepts from a user, and the message for one outside it.
#pragma once

#include <string>

namespace rimu {

/// The spectral values Rimu accepts from a user (CSV columns, inline tables): 0, or a magnitude from 1e-30 to 1e30.
/// Within it every integral Rimu takes (against colour-matching functions, reflectances, a second spectrum) stays a
/// normal double with room to spare, and a value survives conversion to single precision for rendering; beyond it,
/// colorimetry divides subnormal or infinite sums (XYZ "inf", xy "nan"). Scale such data: the colour results are
/// relative, and absolute ones scale with the data.
inline constexpr double kMinSpectralValueMagnitude = 1e-30;
inline constexpr double kMaxSpectralValueMagnitude = 1e30;

/// Empty if `value` is in the accepted range above; else why not, for a message ("1e-310 is nonzero but smaller …").
std::string spectral_value_range_error(double value);

}  // namespace rimu
