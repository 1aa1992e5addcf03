// A medium that contains the camera (docs/scene-format.md, "media": "contains_camera"): camera paths start inside
// it, and without a boundary material it surrounds everything (pbrt-v4's camera medium / scene-wide fog).
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

// An orthographic camera at the origin looking down +z at a two-sided emitter of radiance 1 two metres away that
// fills the frame: every camera ray crosses exactly 2 m before reaching it.
json emitter_scene() {
  return json::parse(R"({
    "camera": {"type": "orthographic", "from": [0, 0, 0], "to": [0, 0, 1], "height": 1},
    "film": {"resolution": [16, 16], "filter": {"type": "box", "radius": 0.5}},
    "integrator": {"spp": 16, "max_depth": 4},
    "materials": {"black": {"type": "diffuse", "reflectance": 0}},
    "shapes": [{"type": "quad", "material": "black", "two_sided": true, "emission": {"rgb": [1, 1, 1]},
                "vertices": [[-2, -2, 2], [2, -2, 2], [2, 2, 2], [-2, 2, 2]]}]
  })");
}

test::Estimate mean_luminance(const json& document, uint64_t seed) {
  const auto scene = test::scene_from_json(document);
  return test::estimate_of(test::luminance_values(*test::render_xyz(*scene, 16, seed).film));
}

}  // namespace

TEST_CASE("camera medium: a camera inside a scene-wide absorber sees the emitter through exp(-sigma_a d)") {
  const test::Estimate vacuum = mean_luminance(emitter_scene(), 1);
  json fog = emitter_scene();
  fog["media"] = {{"fog", {{"type", "homogeneous"}, {"sigma_a", 0.5}, {"sigma_s", 0}, {"contains_camera", true}}}};
  const auto scene = test::scene_from_json(fog);
  CHECK(scene->camera_medium == 0);
  const test::Estimate absorbed = mean_luminance(fog, 2);
  // Beer-Lambert over d = 2 m: T = exp(-0.5 · 2) = e^-1. Both renders are noisy (wavelength sampling; in the fog
  // also whether the free flight passes), and independent (different seeds).
  const double expected = std::exp(-1.0) * vacuum.mean;
  const double standard_error = std::hypot(absorbed.standard_error, std::exp(-1.0) * vacuum.standard_error);
  CAPTURE(absorbed.mean);
  CAPTURE(expected);
  CAPTURE(standard_error);
  CHECK(vacuum.mean > 0.0);
  CHECK(std::fabs(absorbed.mean - expected) <= test::kSigmas * standard_error);
  CHECK(standard_error < 0.02 * expected);  // the check above is tight enough to see a 10 % error
}

TEST_CASE("camera medium: bad contains_camera input is an error at its key") {
  json two = emitter_scene();
  two["media"] = {{"a", {{"type", "homogeneous"}, {"sigma_a", 1}, {"sigma_s", 0}, {"contains_camera", true}}},
                  {"b", {{"type", "homogeneous"}, {"sigma_a", 1}, {"sigma_s", 0}, {"contains_camera", true}}}};
  CHECK_THROWS_WITH_AS(test::scene_from_json(two), doctest::Contains("/media/b/contains_camera: only one medium can contain the camera"),
                       InputError);
  json unbounded = emitter_scene();
  unbounded["media"] = {{"a", {{"type", "homogeneous"}, {"sigma_a", 1}, {"sigma_s", 0}}}};
  CHECK_THROWS_WITH_AS(test::scene_from_json(unbounded), doctest::Contains("/media/a"), InputError);
  json matched = emitter_scene();
  matched["media"] = {{"a", {{"type", "homogeneous"}, {"sigma_a", 1}, {"sigma_s", 0}, {"contains_camera", true}, {"index_matched", true}}}};
  CHECK_THROWS_WITH_AS(test::scene_from_json(matched), doctest::Contains("/media/a/index_matched: a medium without a boundary_material"),
                       InputError);
}
