// A camera path keyed by frame: "camera": {"keyframes": [{"frame": 1, "from": …, "to": …}, …]} in a JSON scene,
// resolved for one frame of a sequence before the scene is loaded (docs/scene-format.md, "Camera paths").
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace rimu {

/// If document["camera"] has "keyframes", replaces them by the camera of `frame`: "from", "to", "up" and
/// "vertical_fov_deg" interpolated linearly between the two keys around `frame` (held constant before the first key
/// and after the last). Each key has an integer "frame" (strictly increasing from key to key), "from" and "to", and
/// optionally "up" and "vertical_fov_deg" (default: the camera's own, else [0, 1, 0] and 40). The camera itself may
/// not also give "from" or "to". Throws InputError naming `file` and the key path on a malformed path, and for a
/// frame whose interpolated camera has no viewing direction or an "up" along it. Without "keyframes": no change.
void apply_camera_keyframes(nlohmann::json& document, int frame, const std::string& file);

}  // namespace rimu
