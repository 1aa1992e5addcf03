// integrator.max_depth_includes_media (docs/scene-format.md, "integrator"): read from the scene, passed by the
// renderer to the volumetric integrator, and refused when it is not a boolean. The transport-level closed forms are
// in tests/transport/media_depth_rule_test.cpp.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

// An orthographic camera inside a scene-wide fog (σ_a = 0.25, σ_s = 0.5 per metre) looking at an emitter of
// radiance 1 two metres away that fills the frame, behind which is nothing: all light comes from the emitter,
// directly (through exp(−σ_t·2)) or scattered in the fog.
json fog_scene(int max_depth) {
  json d = json::parse(R"({
    "camera": {"type": "orthographic", "from": [0, 0, 0], "to": [0, 0, 1], "height": 1},
    "film": {"resolution": [8, 8], "filter": {"type": "box", "radius": 0.5}},
    "integrator": {"spp": 64},
    "materials": {"black": {"type": "diffuse", "reflectance": 0}},
    "media": {"fog": {"type": "homogeneous", "sigma_a": 0.25, "sigma_s": 0.5, "contains_camera": true}},
    "shapes": [{"type": "quad", "material": "black", "two_sided": true, "emission": {"rgb": [1, 1, 1]},
                "vertices": [[-4, -4, 2], [4, -4, 2], [4, 4, 2], [-4, 4, 2]]}]
  })");
  d["integrator"]["max_depth"] = max_depth;
  return d;
}

test::Estimate mean_luminance(const json& document, uint64_t seed) {
  const auto scene = test::scene_from_json(document);
  return test::estimate_of(test::luminance_values(*test::render_xyz(*scene, 64, seed).film));
}

}  // namespace

TEST_CASE("integrator.max_depth_includes_media: at max_depth 0 only the unscattered emitter remains, without it more") {
  const test::Estimate vacuum = [] {
    json d = fog_scene(0);
    d.erase("media");
    return mean_luminance(d, 1);
  }();
  json counted = fog_scene(0);
  counted["integrator"]["max_depth_includes_media"] = true;
  CHECK(test::scene_from_json(counted)->settings.max_depth_includes_media);
  CHECK_FALSE(test::scene_from_json(fog_scene(0))->settings.max_depth_includes_media);  // the default

  // Counted: Beer–Lambert over 2 m, exp(−0.75 · 2), and nothing scattered (independent seeds, so the errors add).
  const test::Estimate direct = mean_luminance(counted, 2);
  const double expected = std::exp(-1.5) * vacuum.mean;
  const double standard_error = std::hypot(direct.standard_error, std::exp(-1.5) * vacuum.standard_error);
  CAPTURE(direct.mean);
  CAPTURE(expected);
  CHECK(std::fabs(direct.mean - expected) <= test::kSigmas * standard_error);
  // Not counted: scattering in the fog adds light at max_depth 0 (the surface-only rule).
  const test::Estimate all = mean_luminance(fog_scene(0), 3);
  CAPTURE(all.mean);
  CHECK(all.mean - direct.mean > test::kSigmas * std::hypot(all.standard_error, direct.standard_error));
}

TEST_CASE("integrator.max_depth_includes_media must be true or false") {
  json d = fog_scene(2);
  d["integrator"]["max_depth_includes_media"] = "yes";
  CHECK_THROWS_WITH_AS(test::scene_from_json(d), doctest::Contains("max_depth_includes_media: expected true or false"),
                       InputError);
}
