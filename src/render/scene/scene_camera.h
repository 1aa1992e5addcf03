// The scene camera's "exposure" and "white_balance" keys, read into the physical camera's settings
// (render/camera/camera_exposure.h, which also takes them from the command line).
#pragma once

#include "render/camera/camera_exposure.h"
#include "render/scene/json_cursor.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

/// Parses a scene camera's "exposure" object: iso, shutter_s, f_number required, compensation_ev optional (0).
PhysicalCameraSettings parse_exposure(const JsonCursor& exposure);
/// Parses "white_balance": {"cct": K}, {"daylight_cct": K}, {"illuminant": name} or "none"; unknown illuminants fail
/// at the key.
WhiteBalanceSettings parse_white_balance(const JsonCursor& white_balance, SpectralLibrary& library);

}  // namespace rimu
