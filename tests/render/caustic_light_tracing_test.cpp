// Caustic light tracing (transport/integrators/caustic_light_tracer.h) through the real render loop: the path tracer
// drops the paths E D S⁺ L of the lights it traces and the light tracer adds them, so the image's mean must stay the
// path tracer's (within the standard error) where the path tracer alone can find those paths too (a floor lit through
// a glass block, seen by a pinhole and by a thin-lens camera); the image is the same for any thread count; a camera
// light tracing cannot connect to (orthographic) keeps the path tracer's caustics; and the caustics go to their
// light's group.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"

using namespace rimu;

namespace {

// A white floor under a black ceiling 1 m up whose 0.6 m square opening is filled by a glass block (n = 1.5, 10 cm
// thick); above it a one-sided 0.8 m square light (or a 15 cm sphere), seen from under the ceiling: the floor's
// light comes through two refractions (E D S S L, and more bounces after it), which BSDF sampling from the floor also
// finds often enough (the light is large), so both estimators converge here.
nlohmann::json glass_block_scene(const char* caustics, const char* light) {
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
  scene["integrator"]["caustics"] = caustics;
  if (std::string(light) == "area") {
    scene["shapes"].push_back({{"type", "quad"}, {"material", "black"},
                               {"vertices", {{-0.4, 1.5, -0.4}, {0.4, 1.5, -0.4}, {0.4, 1.5, 0.4}, {-0.4, 1.5, 0.4}}},
                               {"emission", {{"illuminant", "D65"}, {"scale", 1.0}}}});
  } else {
    scene["shapes"].push_back({{"type", "sphere"}, {"material", "black"}, {"center", {0.0, 1.4, 0.0}}, {"radius", 0.15},
                               {"emission", {{"illuminant", "D65"}, {"scale", 1.0}}}});
  }
  return scene;
}

// A thin lens focused on the floor's middle, 2 cm aperture radius.
nlohmann::json with_thin_lens(nlohmann::json scene) {
  scene["camera"]["type"] = "thin_lens";
  scene["camera"]["lens_radius"] = 0.02;
  scene["camera"]["focus_distance"] = 1.0;
  return scene;
}

void check_same_mean(const char* light, int spp, bool thin_lens = false) {
  nlohmann::json traced_document = glass_block_scene("light_tracing", light);
  nlohmann::json path_traced_document = glass_block_scene("path_tracing", light);
  if (thin_lens) {
    traced_document = with_thin_lens(traced_document);
    path_traced_document = with_thin_lens(path_traced_document);
  }
  const auto traced = test::scene_from_json(traced_document);
  const auto path_traced = test::scene_from_json(path_traced_document);
  const test::RenderedFilm a = test::render_xyz(*traced, spp, 1);
  const test::RenderedFilm b = test::render_xyz(*path_traced, spp, 2);
  CHECK(a.statistics.caustic_light_tracing);
  CHECK_FALSE(b.statistics.caustic_light_tracing);
  const test::Estimate d = test::paired_difference(test::luminance_values(*a.film), test::luminance_values(*b.film));
  const double m = test::mean_of(test::luminance_values(*b.film));
  const std::string label = std::string(light) + (thin_lens ? " (thin lens)" : "");
  INFO(label << ": light-traced − path-traced = " << d.mean << " ± " << d.standard_error << " (mean " << m << ")");
  CHECK(std::fabs(d.mean) <= test::kSigmas * d.standard_error);
  CHECK(d.standard_error > 0.0);
  CHECK(d.standard_error < 0.02 * m);  // a test that could see a few per cent
}

}  // namespace

TEST_CASE("caustic light tracing leaves the image's mean as the path tracer's: area and sphere lights") {
  check_same_mean("area", 512);
  check_same_mean("sphere", 512);
}

TEST_CASE("caustic light tracing through a thin lens leaves the image's mean as the path tracer's") {
  check_same_mean("area", 512, true);
}

TEST_CASE("caustic light tracing gives the same image for any thread count") {
  const auto scene = test::scene_from_json(glass_block_scene("light_tracing", "area"));
  const test::RenderedFilm one = test::render_xyz(*scene, 4, 7, 1);
  const test::RenderedFilm two = test::render_xyz(*scene, 4, 7, 2);
  CHECK(one.statistics.caustic_light_tracing);
  CHECK(test::film_bits(*one.film) == test::film_bits(*two.film));
}

TEST_CASE("an orthographic camera keeps the path tracer's caustics") {
  nlohmann::json document = glass_block_scene("light_tracing", "area");
  document["camera"]["type"] = "orthographic";
  document["camera"]["height"] = 1.5;
  document["camera"].erase("vertical_fov_deg");
  const auto scene = test::scene_from_json(document);
  CHECK_FALSE(test::render_xyz(*scene, 1, 1).statistics.caustic_light_tracing);
}

TEST_CASE("light-traced caustics go to their light's group: the layers still sum to the beauty") {
  // The glass block under two lights of two groups: a square light (light-traced caustics) and an environment
  // (path-traced). Every pixel's two layers sum to its beauty, to double rounding.
  nlohmann::json document = glass_block_scene("light_tracing", "area");
  document["shapes"].back()["light_group"] = "lamp";
  document["lights"] = nlohmann::json::array(
      {{{"type", "environment"}, {"light_group", "sky"}, {"radiance", {{"illuminant", "D65"}, {"scale", 0.2}}}}});
  const auto scene = test::scene_from_json(document);
  REQUIRE(scene->light_groups.size() == 2);
  FilmOptions options{scene->settings.width, scene->settings.height, std::nullopt, 0};
  Film film(options, SpectralResponse::cie_xyz(test::library()), scene->light_groups);
  RenderOptions render_options;
  render_options.samples_per_pixel = 8;
  render_options.seed = 3;
  render_options.threads = 2;
  CHECK(render(*scene, test::filter_of(*scene), film, render_options).caustic_light_tracing);
  double lamp_total = 0.0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const auto beauty = film.pixel_value(x, y);
      const auto a = film.group_value(x, y, 0), b = film.group_value(x, y, 1);
      for (int c = 0; c < 3; ++c) CHECK(a[size_t(c)] + b[size_t(c)] == doctest::Approx(beauty[size_t(c)]).epsilon(1e-9));
      lamp_total += scene->light_groups[0] == "lamp" ? a[1] : b[1];
    }
  CHECK(lamp_total > 0.0);
}

TEST_CASE("light tracing's hard cases write nothing non-finite: a spot inside a glass ball touching a mirror floor") {
  // The spot sits at the ball's centre (every emitted ray meets the glass from inside at normal incidence), the ball
  // touches a smooth gold floor (rays pass between glass and mirror at grazing angles), a 1 µm glass ball floats
  // nearby (tiny scales), and the camera looks along the floor (grazing connections). Nothing may reach the film as
  // NaN or infinity (the film would count and drop such a splat; the REQUIRE sees any that got through), and the
  // image is not black.
  const auto scene = test::scene_from_json(nlohmann::json::parse(R"({
    "camera": {"type": "pinhole", "from": [0.0, 0.02, -1.5], "to": [0.0, 0.0, 0.0], "up": [0, 1, 0],
               "vertical_fov_deg": 60},
    "film": {"resolution": [24, 16]},
    "integrator": {"max_depth": 12, "caustics": "light_tracing"},
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
  })"));
  const test::RenderedFilm rendered = test::render_xyz(*scene, 16, 5);
  CHECK(rendered.statistics.caustic_light_tracing);
  CHECK(test::finite_total(*rendered.film) > 0.0);
}
