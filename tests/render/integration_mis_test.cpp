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

#include <vector>

#include "integration_support.h"
#include "transport/integrators/volumetric_path_integrator.h"

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
  // The glossy half resamples its light among 8 candidates (the quad's two triangles and their points;
  // light_resampling.h), whose target includes the MIS weight, and both techniques' MIS weights there count the
  // light sampler's density 8 times: the three strategies must still agree (with the count on the BSDF side
  // left at 1, MIS was 0.017 (5.5 standard errors) away from NEE-only).
  const nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 1.2, -2.2], "to": [0, 0, 0.2], "vertical_fov_deg": 40},
    "film": {"resolution": [32, 32], "filter": {"type": "box"}},
    "integrator": {"max_depth": 16, "glossy_light_candidates": 8},
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
  // With 8 candidates asked for, the sphere's glossy vertices have a single light to give (its choice probability
  // is 1): they do not resample, and both techniques' weights count the environment's density once
  // (path_integrator.cpp). Counting it 8 times on one side only would bias the MIS image.
  nlohmann::json asked = scene;
  asked["integrator"]["glossy_light_candidates"] = 8;
  check_all_agree(render_strategies(asked, 16, 64, 16));
}

namespace integration_mis_test {

// Two renders of `scene_json` (seeds a, b) with `candidates` lights drawn per glossy vertex.
std::pair<std::vector<double>, std::vector<double>> render_pair(nlohmann::json scene_json, int candidates, int spp,
                                                                uint64_t seed) {
  scene_json["integrator"]["glossy_light_candidates"] = candidates;
  const auto scene = scene_from_json(scene_json);
  const RenderedFilm a = render_xyz(*scene, spp, seed);
  const RenderedFilm b = render_xyz(*scene, spp, seed + 1);
  CHECK(a.film->sample_counts().discarded() == 0);
  return {luminance_values(*a.film), luminance_values(*b.film)};
}

// Σ (a_i − b_i)² / 2: the pixels' summed variance, from two independent renders.
double summed_variance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]) / 2.0;
  return s;
}

// lane_radiance() (integration_support.h) along one ray with the scene's volumetric integrator, set up as the
// renderer sets it up in scenes with media.
std::array<Estimate, 4> volumetric_lane_radiance(const Scene& scene, const Ray& ray, int count, uint64_t seed) {
  const TransportScene view = scene.transport_view();
  const VolumetricScene volumetric{view, &scene.media, &scene.medium_boundaries, scene.camera_medium};
  VolumetricIntegratorSettings settings;
  settings.path = scene.settings.integrator;
  settings.distance = scene.settings.distance_sampling;
  const VolumetricPathIntegrator integrator(volumetric, settings);
  return integrator_lane_radiance(integrator, [&](int) { return ray; }, count, seed);
}

// Along camera rays from `eye` to each target, the estimate with 8 resampled candidates equals, lane by lane, the
// light sampler's own (one candidate: the existing estimator) within kSigmas combined standard errors, resolved to 5 %.
void check_candidates_agree(const nlohmann::json& scene, Vec3 eye, const std::vector<Vec3>& targets, bool volumetric,
                            int count_one = 2000000) {
  for (const Vec3 target : targets) {
    std::array<std::array<Estimate, 4>, 2> lanes;
    for (const int candidates : {1, 8}) {
      nlohmann::json variant = scene;
      variant["integrator"]["glossy_light_candidates"] = candidates;
      const auto loaded = scene_from_json(variant);
      const Ray ray = ray_between(eye, target);
      const int count = candidates == 1 ? count_one : count_one / 10;
      const uint64_t seed = 7 + uint64_t(candidates);
      lanes[candidates == 8] = volumetric ? volumetric_lane_radiance(*loaded, ray, count, seed)
                                          : lane_radiance(*loaded, [&](int) { return ray; }, count, seed);
    }
    for (int j = 0; j < 4; ++j) {
      const Estimate one = lanes[0][size_t(j)], eight = lanes[1][size_t(j)];
      const double se = std::hypot(one.standard_error, eight.standard_error);
      CAPTURE(volumetric);
      CAPTURE(target.x);
      CAPTURE(target.z);
      CAPTURE(j);
      CAPTURE(one.mean);
      CAPTURE(eight.mean);
      CAPTURE(se);
      CHECK(std::abs(one.mean - eight.mean) <= kSigmas * se);
      CHECK(kSigmas * se < 0.05 * one.mean);
    }
  }
}

// 25 point lamps (10 W, 3000 K) in a 5 × 5 grid 1.2 m over a floor of `material`, seen at a slant, direct light only.
nlohmann::json lamps_over_floor(const nlohmann::json& material, int resolution) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 1.0, -3], "to": [0, 0, 0.5], "vertical_fov_deg": 40},
    "film": {"filter": {"type": "box"}},
    "integrator": {"max_depth": 1},
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-4, 0, -4], [-4, 0, 6], [4, 0, 6], [4, 0, -4]]}],
    "lights": []
  })");
  scene["film"]["resolution"] = {resolution, resolution};
  scene["materials"]["floor"] = material;
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 5; ++k)
      scene["lights"].push_back({{"type", "point"}, {"position", {-1.6 + 0.8 * i, 1.2, -0.5 + 0.8 * k}},
                                 {"radiant_power_w", 10.0}, {"spectrum", {{"blackbody", 3000}}}});
  return scene;
}

// Two renders each way (seeds `seed`, +1 with one candidate; +10, +11 with 8): the pixels' summed variance is at
// least halved by the resampling.
void check_variance_halved(const nlohmann::json& scene, int spp, uint64_t seed) {
  const auto [one_a, one_b] = render_pair(scene, 1, spp, seed);
  const auto [eight_a, eight_b] = render_pair(scene, 8, spp, seed + 10);
  const double variance_one = summed_variance(one_a, one_b), variance_eight = summed_variance(eight_a, eight_b);
  CAPTURE(variance_one);
  CAPTURE(variance_eight);
  CHECK(variance_eight * 2.0 < variance_one);
}

}  // namespace integration_mis_test

TEST_CASE("MIS: 25 point lights over rough copper, the resampled light choice is unbiased and lowers the variance") {
  // α = 0.01 (roughness 0.1): each pixel of the floor passes light from the one or two lamps inside its narrow
  // lobe, which the light tree (weighing lamps by irradiance) picks no more often than the others. Resampling among
  // 8 candidates (light_resampling.h) must give the same image in mean, with the variance of the glints cut:
  // with 25 similar lamps the lobe's lamp is among the candidates about 8× as often.
  using namespace integration_mis_test;
  const nlohmann::json scene =
      lamps_over_floor(nlohmann::json::parse(R"({"type": "conductor", "metal": "copper", "roughness": 0.1})"), 32);
  // Unbiased: along fixed camera rays (at a lamp's glint, beside it, and between lamps), the resampled estimate
  // per lane equals the light sampler's own; and the same in the volumetric integrator (an absorbing fog around
  // everything: scenes with media resample too), at the glint and beside it.
  check_candidates_agree(scene, {0, 1.0f, -3}, {{0, 0, -1.5f}, {0.2f, 0, -1.2f}, {1.0f, 0, 0.5f}}, false);
  nlohmann::json foggy = scene;
  foggy["media"] = {{"fog", {{"type", "homogeneous"}, {"sigma_a", 0.05}, {"sigma_s", 0}, {"contains_camera", true}}}};
  check_candidates_agree(foggy, {0, 1.0f, -3}, {{0, 0, -1.5f}, {0.2f, 0, -1.2f}}, true);
  // Less variance: two renders each way, the pixels' summed variance.
  check_variance_halved(scene, 64, 31);
}

TEST_CASE("MIS: 25 point lights over lacquered copper (a smooth coat on a glossy metal) resample as the bare metal") {
  // The coated conductor's lobe is the metal's, refracted through the coat: as narrow, so its vertices are glossy
  // (LayeredBsdf::flags) and resample their light. Its f is a random walk's estimate, a deterministic function of
  // the two directions (layered_bsdf.h), so the resampling target and the estimate use the same f: unbiased.
  using namespace integration_mis_test;
  const nlohmann::json scene = lamps_over_floor(nlohmann::json::parse(R"({"type": "coated_conductor", "metal": "copper",
                                                 "conductor_roughness": 0.1, "coat_ior": 1.5})"), 24);
  check_candidates_agree(scene, {0, 1.0f, -3}, {{0.2f, 0, -1.2f}}, false, 500000);
  check_variance_halved(scene, 32, 51);
}

TEST_CASE("glossy_light_candidates: auto resamples in scenes of many lights only, explicit counts and errors") {
  PathIntegratorSettings settings;
  CHECK(settings.glossy_candidates_for(3) == 1);
  CHECK(settings.glossy_candidates_for(PathIntegratorSettings::kManyLights) == PathIntegratorSettings::kManyLightsCandidates);
  settings.glossy_light_candidates = 4;
  CHECK(settings.glossy_candidates_for(1) == 4);
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 1, -3], "to": [0, 0, 0], "vertical_fov_deg": 40},
    "film": {"resolution": [4, 4]},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [{"type": "quad", "material": "grey", "vertices": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]}],
    "lights": [{"type": "environment", "radiance": 1}]
  })");
  scene["integrator"]["glossy_light_candidates"] = "auto";
  CHECK(scene_from_json(scene)->settings.integrator.glossy_light_candidates == 0);
  scene["integrator"]["glossy_light_candidates"] = 16;
  CHECK(scene_from_json(scene)->settings.integrator.glossy_light_candidates == 16);
  for (const nlohmann::json& bad : {nlohmann::json("many"), nlohmann::json(0), nlohmann::json(65)}) {
    scene["integrator"]["glossy_light_candidates"] = bad;
    CHECK_THROWS_WITH(scene_from_json(scene), doctest::Contains("glossy_light_candidates"));
  }
}
