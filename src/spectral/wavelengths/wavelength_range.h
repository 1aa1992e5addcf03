// The wavelength range Rimu transports and integrates over.
#pragma once

namespace rimu {

/// The CIE 1931/1964 observers are tabulated over 360-830 nm (CIE 15:2004); Rimu samples the same range,
/// so no part of any observer's response is cut off.
inline constexpr double kLambdaMinNm = 360.0;
inline constexpr double kLambdaMaxNm = 830.0;

}  // namespace rimu
