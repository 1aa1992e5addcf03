// The scene's and the command line's physical camera: exposure settings and white balance as given, and the film
// output transform they resolve to (render/film/film_output_transform.h, applied when the film is written).
//
//   "camera": {..., "exposure": {"iso": 100, "shutter_s": 0.01, "f_number": 16, "compensation_ev": 0},
//                   "white_balance": {"cct": 2700} | {"daylight_cct": 6504} | {"illuminant": "A"} | "none"}
//
// Without "exposure" the film is written in film units (Y = 1 ↔ 72 983 nt for an XYZ film), as before. With it,
// values are multiplied by the imaging ratio of physical_camera.h, so a surface at the metered luminance
// K N²/(t S) (K = 12.5) is written as 0.18. A white balance "cct" is a Planckian (blackbody) white of that
// temperature, as a camera's Kelvin setting is; "daylight_cct" is CIE daylight of that correlated colour temperature
// (S0 + M1·S1 + M2·S2, unrounded M, 4000-25000 K: pbrt-v4's "whitebalance"); "illuminant" is a CIE illuminant by name.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "render/film/film_output_transform.h"
#include "render/camera/physical_camera.h"
#include "render/film/spectral_response.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

/// The white the camera is balanced to.
struct WhiteBalanceSettings {
  enum class Kind { none, cct, daylight, illuminant };
  Kind kind = Kind::none;
  double cct_k = 0;        ///< Kind::cct: a blackbody of this temperature, 1000-25000 K; Kind::daylight: CIE
                           ///< daylight of this correlated colour temperature, 4000-25000 K
  std::string illuminant;  ///< Kind::illuminant: a CIE illuminant name (SpectralLibrary::illuminant)

  /// "none", "2700 K", "daylight 6504 K", "illuminant A": for metadata and messages.
  std::string describe() const;
  /// The settings describe() gave `text` for (an EXR's rimu:whiteBalance), or nothing if it is not such a text.
  static std::optional<WhiteBalanceSettings> from_description(const std::string& text);
};

/// The physical camera of a render: no exposure means film units.
struct CameraExposureSettings {
  std::optional<PhysicalCameraSettings> exposure;
  WhiteBalanceSettings white_balance;
};

/// The physical camera's accepted ranges, the same for the scene's "exposure" keys and the command line's options:
/// ISO 0.001-10 000 000, shutter 1 ns-10⁶ s, f/0.1-f/1000, compensation ±30 EV. Inside them the imaging ratio
/// (physical_camera.h) stays within about 10^±30, far inside a double and a float.
struct PhysicalCameraRange {
  const char* what;
  double min, max;
};
inline constexpr PhysicalCameraRange kIsoRange{"an ISO speed", 1e-3, 1e7};
inline constexpr PhysicalCameraRange kShutterRange_s{"a shutter time in seconds", 1e-9, 1e6};
inline constexpr PhysicalCameraRange kFNumberRange{"an f-number", 0.1, 1000.0};
inline constexpr PhysicalCameraRange kCompensationRange_ev{"an exposure compensation in stops", -30.0, 30.0};

/// Blackbody CCTs accepted for white balance: the range rimu-light and the scene's {"blackbody": T} accept.
inline constexpr double kMinCct_k = 1000.0, kMaxCct_k = 25000.0;
/// CIE daylight (CIE 15:2004 eqs. 3.3-3.4) is defined from 4000 K up.
inline constexpr double kMinDaylightCct_k = 4000.0;

/// Throws InputError naming `option` unless min <= value <= max (so NaN and ±Inf fail too).
void check_camera_option(double value, const PhysicalCameraRange& range, const std::string& option);

/// Parses the command line's --white-balance: "none", a temperature ("2700" or "2700K"), or an illuminant name.
WhiteBalanceSettings parse_white_balance_option(const std::string& text, SpectralLibrary& library,
                                                const std::string& option);
/// Parses a shutter time in seconds given as "0.01" or "1/100"; InputError naming `option` otherwise.
double parse_shutter_time_s(const std::string& text, const std::string& option);

/// The illuminant a white balance neutralises (a blackbody of peak 1, a CIE daylight, or a named illuminant); null for
/// none.
SpectrumPtr white_balance_illuminant(const WhiteBalanceSettings& white_balance, SpectralLibrary& library);

/// The exposure scale and white-balance matrix for a film of `response`. Throws InputError if the film sees no
/// light from the white-balance illuminant in some channel.
FilmOutputTransform film_output_transform(const CameraExposureSettings& camera, const SpectralResponse& response,
                                          SpectralLibrary& library);

/// EXR metadata (keys without the "rimu:" prefix): iso, shutterSeconds, fNumber, exposureCompensationEV, EV,
/// meteredLuminanceNits, exposureScale, whiteBalance. Empty without a physical camera or white balance.
std::map<std::string, std::string> exposure_metadata(const CameraExposureSettings& camera,
                                                     const FilmOutputTransform& transform);

}  // namespace rimu
