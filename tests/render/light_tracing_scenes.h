// The scenes the light-tracing tests share (caustic_light_tracing_test.cpp, bidirectional_test.cpp): a floor lit
// through a glass block, and a hard case (a spot inside a glass ball on a mirror).
#pragma once

#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace rimu::test {

/// A white floor under a black ceiling 1 m up whose 0.6 m square opening is filled by a glass block (n = 1.5, 10 cm
/// thick), seen from under the ceiling and lit from above through the block, so that the floor's light comes through
/// two refractions (E D S S L, and more bounces after it), by `light`: "area", a one-sided 0.8 m square light, or "sphere", a 15 cm sphere (both
/// large enough that BSDF sampling from the floor also finds them, so a path tracer converges too); or "spot", a
/// 60° spot (a light at a point: only light paths find it through the glass).
inline nlohmann::json glass_block_scene(const std::string& light) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"type": "pinhole", "from": [0.0, 0.6, -0.9], "to": [0.0, 0.0, 0.2], "up": [0, 1, 0],
               "vertical_fov_deg": 50},
    "film": {"resolution": [32, 24], "filter": {"type": "gaussian"}},
    "integrator": {"max_depth": 6},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.8}, "black": {"type": "diffuse", "reflectance": 0},
                  "glass": {"type": "dielectric", "ior": 1.5}},
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]},
      {"type": "quad", "material": "black", "vertices": [[-2, 1, -2], [-0.3, 1, -2], [-0.3, 1, 2], [-2, 1, 2]]},
      {"type": "quad", "material": "black", "vertices": [[0.3, 1, -2], [2, 1, -2], [2, 1, 2], [0.3, 1, 2]]},
      {"type": "quad", "material": "black", "vertices": [[-0.3, 1, -2], [0.3, 1, -2], [0.3, 1, -0.3], [-0.3, 1, -0.3]]},
      {"type": "quad", "material": "black", "vertices": [[-0.3, 1, 0.3], [0.3, 1, 0.3], [0.3, 1, 2], [-0.3, 1, 2]]},
      {"type": "box", "material": "glass", "min": [-0.3, 0.95, -0.3], "max": [0.3, 1.05, 0.3]}
    ]})");
  if (light == "area") {
    scene["shapes"].push_back({{"type", "quad"}, {"material", "black"},
                               {"vertices", {{-0.4, 1.5, -0.4}, {0.4, 1.5, -0.4}, {0.4, 1.5, 0.4}, {-0.4, 1.5, 0.4}}},
                               {"emission", {{"illuminant", "D65"}, {"scale", 1.0}}}});
  } else if (light == "sphere") {
    scene["shapes"].push_back({{"type", "sphere"}, {"material", "black"}, {"center", {0.0, 1.4, 0.0}}, {"radius", 0.15},
                               {"emission", {{"illuminant", "D65"}, {"scale", 1.0}}}});
  } else if (light == "spot") {
    scene["lights"] = nlohmann::json::array({{{"type", "spot"}, {"position", {0.0, 1.5, 0.0}},
                                             {"direction", {0.0, -1.0, 0.0}}, {"cone_angle_deg", 60},
                                             {"intensity", {{"illuminant", "D65"}, {"scale", 1.0}}}}});
  } else {
    throw std::invalid_argument("glass_block_scene: no light '" + light + "'");
  }
  return scene;
}

/// `scene` (the glass block with its square light) in two light groups: the square light "lamp" and a sky "sky".
inline nlohmann::json with_lamp_and_sky_groups(nlohmann::json scene) {
  scene["shapes"].back()["light_group"] = "lamp";
  scene["lights"] = nlohmann::json::array(
      {{{"type", "environment"}, {"light_group", "sky"}, {"radiance", {{"illuminant", "D65"}, {"scale", 0.2}}}}});
  return scene;
}

/// `scene` seen through a thin lens focused on the floor's middle, 2 cm aperture radius.
inline nlohmann::json with_thin_lens(nlohmann::json scene) {
  scene["camera"]["type"] = "thin_lens";
  scene["camera"]["lens_radius"] = 0.02;
  scene["camera"]["focus_distance"] = 1.0;
  return scene;
}

/// The hard case: a spot at the centre of a glass ball (every emitted ray meets the glass from inside at normal
/// incidence) that touches a smooth gold floor (rays pass between glass and mirror at grazing angles), a 1 µm glass
/// ball nearby (tiny scales), a diffuse wall behind, and a camera looking along the floor (grazing connections).
inline nlohmann::json spot_in_glass_ball_scene() {
  return nlohmann::json::parse(R"({
    "camera": {"type": "pinhole", "from": [0.0, 0.02, -1.5], "to": [0.0, 0.0, 0.0], "up": [0, 1, 0],
               "vertical_fov_deg": 60},
    "film": {"resolution": [24, 16]},
    "integrator": {"max_depth": 12},
    "materials": {"mirror": {"type": "conductor", "metal": "gold"}, "wall": {"type": "diffuse", "reflectance": 0.7},
                  "glass": {"type": "dielectric", "ior": 1.5}},
    "shapes": [
      {"type": "quad", "material": "mirror", "vertices": [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]},
      {"type": "quad", "material": "wall", "vertices": [[-2, 0, 1], [-2, 2, 1], [2, 2, 1], [2, 0, 1]]},
      {"type": "sphere", "material": "glass", "center": [0.0, 0.2, 0.0], "radius": 0.2},
      {"type": "sphere", "material": "glass", "center": [0.5, 0.3, 0.0], "radius": 1e-6}
    ],
    "lights": [{"type": "spot", "position": [0.0, 0.2, 0.0], "direction": [0.0, 0.3, 1.0], "cone_angle_deg": 170,
                "intensity": {"illuminant": "D65", "scale": 1.0}}]
  })");
}

}  // namespace rimu::test
