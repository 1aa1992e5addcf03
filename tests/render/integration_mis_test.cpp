// MIS consistency: next-event estimation alone, BSDF sampling alone, and their power-heuristic combination are
// three unbiased estimators of the same image (docs/transport.md: the MIS weights partition unity over the
// techniques), so their pixel means must agree. A weight that does not sum to one, a pdf in the wrong measure
// (area vs solid angle), or a light seen from its back would show up as a difference between them.
//
// Error bars: the three renders use different seeds, so their pixels are independent; the mean over pixels of
// a_i − b_i has the standard error paired_difference() computes (integration_support.h), and the check is
// |mean difference| ≤ kSigmas·SE. Each case also asserts that this bound is tight (a few % of the image mean),
// so the test could detect a bias of that size.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"

using namespace rimu;
using namespace rimu::test;

namespace {

struct StrategyImages {
  std::vector<double> mis, nee_only, bsdf_only;
};

// Renders the scene once per strategy, each with its own sample count (the weaker strategy of a scene gets more
// samples so that the comparison resolves a few % of the image mean: BSDF sampling finds small lights rarely,
// NEE's uniform sphere sampling of an environment serves glossy lobes poorly).
StrategyImages render_strategies(nlohmann::json scene_json, int mis_spp, int nee_only_spp, int bsdf_only_spp) {
  StrategyImages out;
  const std::pair<const char*, std::vector<double>*> strategies[] = {
      {"mis", &out.mis}, {"nee_only", &out.nee_only}, {"bsdf_only", &out.bsdf_only}};
  uint64_t seed = 21;
  for (const auto& [name, image] : strategies) {
    scene_json["integrator"]["direct_lighting"] = name;
    const auto scene = scene_from_json(scene_json);
    const std::string n = name;
    const int spp = n == "mis" ? mis_spp : n == "nee_only" ? nee_only_spp : bsdf_only_spp;
    const RenderedFilm rendered = render_xyz(*scene, spp, seed++);
    CHECK(rendered.film->sample_counts().discarded() == 0);
    *image = luminance_values(*rendered.film);
  }
  return out;
}

void check_agree(const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
  const Estimate difference = paired_difference(a, b);
  const double image_mean = mean_of(a);
  CAPTURE(what);
  CAPTURE(image_mean);
  CAPTURE(difference.mean);
  CAPTURE(difference.standard_error);
  CHECK(std::abs(difference.mean) <= kSigmas * difference.standard_error);
  CHECK(kSigmas * difference.standard_error < 0.05 * image_mean);
}

void check_all_agree(const StrategyImages& images) {
  check_agree(images.mis, images.nee_only, "mis - nee_only");
  check_agree(images.mis, images.bsdf_only, "mis - bsdf_only");
  check_agree(images.nee_only, images.bsdf_only, "nee_only - bsdf_only");
}

}  // namespace

TEST_CASE("MIS: a one-sided quad light over a diffuse and a glossy floor, NEE-only, BSDF-only and MIS agree") {
  // A 0.6 m square light facing down 1 m above a floor whose left half is Lambertian and right half a rough
  // gold-like conductor (roughness 0.3, α = 0.09: a glossy lobe that BSDF sampling finds well and NEE poorly).
  // The light's own (white) surface takes part: light bounces between floor and light.
  const nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 1.2, -2.2], "to": [0, 0, 0.2], "vertical_fov_deg": 40},
    "film": {"resolution": [32, 32], "filter": {"type": "box"}},
    "integrator": {"max_depth": 16},
    "materials": {
      "matte": {"type": "diffuse", "reflectance": 0.7},
      "glossy": {"type": "conductor", "metal": "gold", "roughness": 0.3},
      "white": {"type": "diffuse", "reflectance": 0.8}
    },
    "shapes": [
      {"type": "quad", "material": "matte", "vertices": [[-3, 0, -3], [-3, 0, 3], [0, 0, 3], [0, 0, -3]]},
      {"type": "quad", "material": "glossy", "vertices": [[0, 0, -3], [0, 0, 3], [3, 0, 3], [3, 0, -3]]},
      {"type": "quad", "material": "white", "emission": 4,
       "vertices": [[-0.3, 1, -0.3], [0.3, 1, -0.3], [0.3, 1, 0.3], [-0.3, 1, 0.3]]}
    ]
  })");
  // NEE-only gets 64 spp: the light tree (the default light sampler) chooses one of the quad's two triangles per
  // sample, so the point's 2D Sobol' stratification covers a triangle rather than the quad, and NEE alone is
  // ~2.4× noisier here than when the whole quad was sampled at once.
  check_all_agree(render_strategies(scene, 32, 64, 128));
}

TEST_CASE("MIS: a constant environment over a diffuse floor with a glossy sphere, the three strategies agree") {
  // Ambient occlusion under the sphere, and the sphere's glossy reflection of floor and sky: every direct-light
  // estimate involves the environment (an infinite light found by NEE through its sphere sampling and by
  // escaping BSDF rays).
  const nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 1.5, -3], "to": [0, 0.3, 0], "vertical_fov_deg": 35},
    "film": {"resolution": [32, 32], "filter": {"type": "box"}},
    "integrator": {"max_depth": 16},
    "materials": {
      "matte": {"type": "diffuse", "reflectance": 0.6},
      "glossy": {"type": "conductor", "metal": "copper", "roughness": 0.4}
    },
    "shapes": [
      {"type": "quad", "material": "matte", "vertices": [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]},
      {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "glossy"}
    ],
    "lights": [{"type": "environment", "radiance": 1}]
  })");
  check_all_agree(render_strategies(scene, 16, 64, 16));
}
