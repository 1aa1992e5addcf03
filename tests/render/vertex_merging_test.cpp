// Vertex connection and merging (transport/integrators/vertex_merging.h, `"method": "vcm"`) through the real render
// loop: it must converge to the path tracer's image where the path tracer finds every path (merging is consistent:
// its bias shrinks with the radius, chosen here far below what the test can see), including a floor seen through
// water and lit through it (E S D S L), which no connection can join and which merging finds at a fraction of the
// error; it is deterministic for any thread count and writes nothing non-finite on hard cases.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"
#include "light_tracing_scenes.h"

using namespace rimu;

namespace {

nlohmann::json with_method(nlohmann::json scene, const char* method) {
  scene["integrator"]["method"] = method;
  return scene;
}

// A pool: a diffuse floor under 10 cm of water, a small sphere lamp above. The floor is seen through the water and
// lit through it: every path is E S S D S S L (the water's two surfaces on either side), which next-event
// estimation and every join cannot make (both ends of each join would sit on a refracting surface); only a camera
// path that hits the lamp by BSDF sampling, or a merge at the floor, finds it.
nlohmann::json pool_scene() {
  return nlohmann::json::parse(R"({
    "camera": {"type": "pinhole", "from": [0.0, 0.9, -0.7], "to": [0.0, 0.0, 0.0], "up": [0, 1, 0],
               "vertical_fov_deg": 45},
    "film": {"resolution": [32, 24], "filter": {"type": "gaussian"}},
    "integrator": {"max_depth": 8, "merge_radius": 0.03},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.8}, "black": {"type": "diffuse", "reflectance": 0},
                  "water": {"type": "dielectric", "ior": 1.33}},
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-0.6, 0, -0.6], [-0.6, 0, 0.6], [0.6, 0, 0.6], [0.6, 0, -0.6]]},
      {"type": "box", "material": "water", "min": [-0.6, 0.15, -0.6], "max": [0.6, 0.25, 0.6]},
      {"type": "sphere", "material": "black", "center": [0.15, 0.6, 0.2], "radius": 0.05,
       "emission": {"illuminant": "D65", "scale": 1.0}}
    ]
  })");
}

// `document` rendered with vertex merging (seed 2) against the path tracer (seed 1): the mean paired luminance
// difference and every 8 × 8 block's within kSigmas standard errors, and a standard error small enough to see a few
// per cent.
void check_agrees_with_path_tracer(const nlohmann::json& document, int spp, int reference_spp, const char* what) {
  const auto merged = test::scene_from_json(with_method(document, "vcm"));
  const auto reference = test::scene_from_json(with_method(document, "path_tracing"));
  const test::RenderedFilm a = test::render_xyz(*merged, spp, 2);
  const test::RenderedFilm b = test::render_xyz(*reference, reference_spp, 1);
  CHECK(a.statistics.bidirectional);
  CHECK(a.statistics.vertex_merging);
  CHECK(a.statistics.merge_vertices > 0);
  const std::vector<double> la = test::luminance_values(*a.film), lb = test::luminance_values(*b.film);
  const test::Estimate d = test::paired_difference(la, lb);
  const double m = test::mean_of(lb);
  INFO(std::string(what) << ": merging − path tracer = " << d.mean << " ± " << d.standard_error << " (mean " << m << ")");
  CHECK(d.standard_error > 0.0);
  CHECK(std::fabs(d.mean) <= test::kSigmas * d.standard_error);
  CHECK(d.standard_error < 0.02 * m);
  const std::vector<double> blocks = test::block_deviations(la, lb, a.film->width(), a.film->height(), 8);
  CHECK(test::worst_deviation(blocks) <= test::kSigmas);
}

}  // namespace

TEST_CASE("vertex connection and merging converges to the path tracer's image: area light, sphere light") {
  check_agrees_with_path_tracer(test::glass_block_scene("area"), 128, 256, "area light");
  check_agrees_with_path_tracer(test::glass_block_scene("sphere"), 384, 768, "sphere light");
}

TEST_CASE("vertex merging finds a floor seen through water and lit through it (E S D S L) at a fraction of the error") {
  check_agrees_with_path_tracer(pool_scene(), 512, 8192, "pool");
  // Bidirectional path tracing is no better than the path tracer here (no join can make these paths); merging is:
  // its per-pixel relative variance at equal samples (half the relative mean squared difference of two seeds) must
  // be below half of bidirectional's (measured: 0.16 against 37).
  const auto variance = [](const char* method) {
    const auto scene = test::scene_from_json(with_method(pool_scene(), method));
    const std::vector<double> a = test::luminance_values(*test::render_xyz(*scene, 256, 3).film);
    const std::vector<double> b = test::luminance_values(*test::render_xyz(*scene, 256, 4).film);
    return 0.5 * test::relative_mse(a, b);
  };
  const double merged = variance("vcm"), connected = variance("bidirectional");
  INFO("relative variance per pixel at 256 spp: merging " << merged << ", bidirectional " << connected);
  CHECK(merged < 0.5 * connected);
}

TEST_CASE("vertex connection and merging gives the same image for any thread count") {
  const auto scene = test::scene_from_json(with_method(pool_scene(), "vcm"));
  const test::RenderedFilm one = test::render_xyz(*scene, 6, 7, 1);
  const test::RenderedFilm two = test::render_xyz(*scene, 6, 7, 2);
  CHECK(one.statistics.vertex_merging);
  CHECK(test::film_bits(*one.film) == test::film_bits(*two.film));
}

TEST_CASE("vertex connection and merging's hard cases write nothing non-finite") {
  // A spot inside a glass ball on a mirror, a 1 µm ball, a grazing camera (light_tracing_scenes.h), with a rough
  // coated wall: photons arrive at grazing angles and through specular chains.
  nlohmann::json document = with_method(test::spot_in_glass_ball_scene(), "vcm");
  document["materials"]["wall"] = {{"type", "coated_diffuse"}, {"reflectance", 0.7}, {"roughness", 0.2}};
  document["integrator"]["merge_radius"] = 0.05;
  const test::RenderedFilm rendered = test::render_xyz(*test::scene_from_json(document), 16, 5);
  CHECK(rendered.statistics.vertex_merging);
  CHECK(test::finite_total(*rendered.film) > 0.0);
}
