// Environment portals leave the image unchanged: a room lit through a window by a sky (constant and image),
// rendered with and without a portal on the window, agrees within the standard error of the pixel differences
// (test::paired_difference, test::kSigmas). Also when the portal covers only half the window, so that part of the
// sky's light reaches the room only by BSDF sampling (its MIS weight must then be 1), and when the camera sees the
// sky through the window. Plus the loader's errors for portals that are not rectangles.
#include <doctest/doctest.h>

#include <string>

#include "integration_support.h"
#include "render/scene/json_cursor.h"
#include "render/scene/scene.h"

using namespace rimu;

namespace {

/// A 4 m × 3 m × 4 m closed room (diffuse walls) with a 1.6 m × 1 m window in the +x wall, a dim ceiling panel so
/// the tree has a finite light too, and a sky; `camera_sees_sky` points the camera at the window.
nlohmann::json window_room(bool camera_sees_sky) {
  nlohmann::json d = nlohmann::json::parse(R"({
    "film": {"resolution": [20, 16], "filter": {"type": "box"}},
    "integrator": {"max_depth": 4},
    "materials": {"wall": {"type": "diffuse", "reflectance": 0.6}, "floor": {"type": "diffuse", "reflectance": 0.3},
                  "black": {"type": "diffuse", "reflectance": 0}},
    "lights": [{"type": "environment", "name": "sky", "radiance": {"illuminant": "D65", "scale": 0.01}}],
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-2, 0, 2], [2, 0, 2], [2, 0, -2], [-2, 0, -2]]},
      {"type": "quad", "material": "wall", "vertices": [[-2, 3, -2], [2, 3, -2], [2, 3, 2], [-2, 3, 2]]},
      {"type": "quad", "material": "wall", "vertices": [[-2, 0, -2], [2, 0, -2], [2, 3, -2], [-2, 3, -2]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 0, 2], [-2, 0, 2], [-2, 3, 2], [2, 3, 2]]},
      {"type": "quad", "material": "wall", "vertices": [[-2, 0, 2], [-2, 0, -2], [-2, 3, -2], [-2, 3, 2]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 0, -2], [2, 0, 2], [2, 1, 2], [2, 1, -2]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 2, -2], [2, 2, 2], [2, 3, 2], [2, 3, -2]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 1, -2], [2, 1, -0.8], [2, 2, -0.8], [2, 2, -2]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 1, 0.8], [2, 1, 2], [2, 2, 2], [2, 2, 0.8]]},
      {"type": "quad", "material": "black", "vertices": [[-0.2, 2.99, -0.2], [0.2, 2.99, -0.2], [0.2, 2.99, 0.2], [-0.2, 2.99, 0.2]],
       "emission": {"blackbody": 3000, "scale": 0.5}}
    ]
  })");
  d["camera"] = camera_sees_sky ? nlohmann::json{{"from", {-1.8, 1.5, 0}}, {"to", {2, 1.5, 0}}, {"vertical_fov_deg", 60}}
                                : nlohmann::json{{"from", {-1.8, 2.5, -1.8}}, {"to", {1, 0.5, 1}}, {"vertical_fov_deg", 70}};
  return d;
}

/// With portal `portal` on the sky against without, same sampler, different seeds.
test::Estimate with_against_without(nlohmann::json document, const nlohmann::json& portal, int spp,
                                    double* mean_without) {
  const auto without = test::scene_from_json(document, "without.json");
  document["lights"][0]["portals"] = nlohmann::json::array({portal});
  const auto with = test::scene_from_json(document, "with.json");
  const auto a = test::luminance_values(*test::render_xyz(*with, spp, 303).film);
  const auto b = test::luminance_values(*test::render_xyz(*without, spp, 404).film);
  *mean_without = test::mean_of(b);
  return test::paired_difference(a, b);
}

const nlohmann::json kWholeWindow = {{2, 1, -0.8}, {2, 1, 0.8}, {2, 2, 0.8}, {2, 2, -0.8}};
const nlohmann::json kHalfWindow = {{2, 1, -0.8}, {2, 1, 0.0}, {2, 2, 0.0}, {2, 2, -0.8}};

}  // namespace

TEST_CASE("environment portal: the window room renders the same with and without a portal") {
  struct Case {
    const char* name;
    bool camera_sees_sky;
    const nlohmann::json* portal;
    const char* sampler;
  };
  for (const Case& c : {Case{"whole window, bvh", false, &kWholeWindow, "bvh"},
                        Case{"whole window, power", false, &kWholeWindow, "power"},
                        Case{"half the window (the rest by BSDF sampling only), bvh", false, &kHalfWindow, "bvh"},
                        Case{"camera looking out of the window, bvh", true, &kWholeWindow, "bvh"}}) {
    nlohmann::json document = window_room(c.camera_sees_sky);
    document["integrator"]["light_sampler"] = c.sampler;
    double mean_without = 0.0;
    const test::Estimate d = with_against_without(document, *c.portal, 48, &mean_without);
    INFO(std::string(c.name) << ": mean Y without a portal " << mean_without << ", with − without " << d.mean << " ± "
                << d.standard_error);
    CHECK(mean_without > 0.0);
    CHECK(std::fabs(d.mean) <= test::kSigmas * d.standard_error);
  }
}

TEST_CASE("environment portal: corners that are not a rectangle are refused with the JSON key") {
  for (const char* corners : {"[[2, 1, -0.8], [2, 1, 0.8], [2, 2, 1.2], [2, 2, -0.4]]",  // a parallelogram
                              "[[2, 1, -0.8], [2, 1, 0.8], [2, 2, 0.8]]",                // three corners
                              "[[2, 1, -0.8], [2, 1, -0.8], [2, 1, -0.8], [2, 1, -0.8]]"}) {
    nlohmann::json document = window_room(false);
    document["lights"][0]["portals"] = nlohmann::json::array({nlohmann::json::parse(corners)});
    CAPTURE(corners);
    try {
      test::scene_from_json(document, "bad.json");
      FAIL("accepted");
    } catch (const InputError& error) {
      CHECK(error.where().key == "/lights/0/portals/0");
      CHECK(std::string(error.what()).find("rectangle") != std::string::npos);
    }
  }
}
