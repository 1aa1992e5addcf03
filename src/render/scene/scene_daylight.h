// The daylight lights of a scene: "cie_sky" (a CIE standard general sky, transport/lights/sky/cie_sky_light.h) and
// "sun" (a distant light of the sun's angular size placed by date, time and place). Internal to scene loading;
// docs/scene-format.md ("Daylight") describes the keys.
//
//   {"type": "cie_sky", "sky_type": 12, "sun_position": {...}, "diffuse_horizontal_illuminance_lx": 20000,
//    "cct": 6500, "up": [0, 1, 0], "north": [0, 0, -1]}
//   {"type": "sun", "sun_position": {...}, "spectrum": {"daylight": 5500}, "illuminance_lx": 80000,
//    "angular_diameter_deg": 0.53}
//
// A sun below the horizon is a load-time warning (Scene::warnings) naming the light, the elevation and the place
// and time: a "sun" light then emits nothing; a "cie_sky" keeps its (extrapolated) distribution.
#pragma once

#include <memory>

#include "render/scene/scene_load_context.h"
#include "transport/lights/light.h"

namespace rimu::scene_loading {

/// Loads a "cie_sky" light; errors name the key.
std::unique_ptr<Light> load_cie_sky_light(const JsonCursor& light, LoadContext& context);
/// Loads a "sun" light; errors name the key.
std::unique_ptr<Light> load_sun_light(const JsonCursor& light, LoadContext& context);

}  // namespace rimu::scene_loading
