// Caustic light tracing (transport/integrators/caustic_light_tracer.h) through the real render loop: the path tracer
// drops the paths E D S⁺ L of the lights it traces and the light tracer adds them, so the image's mean must stay the
// path tracer's (within the standard error) where the path tracer alone can find those paths too (a floor lit through
// a glass block, seen by a pinhole and by a thin-lens camera); the image is the same for any thread count; a camera
// light tracing cannot connect to (orthographic) keeps the path tracer's caustics; and the caustics go to their
// light's group.
#include <doctest/doctest.h>

#include <cmath>

#include "light_tracing_scenes.h"
#include "integration_support.h"

using namespace rimu;

namespace {

// The shared glass-block scene (glass_block_scene.h) with integrator.caustics `caustics`.
nlohmann::json glass_block_scene(const char* caustics, const char* light) {
  nlohmann::json scene = test::glass_block_scene(light);
  scene["integrator"]["caustics"] = caustics;
  return scene;
}

void check_same_mean(const char* light, int spp, bool thin_lens = false) {
  nlohmann::json traced_document = glass_block_scene("light_tracing", light);
  nlohmann::json path_traced_document = glass_block_scene("path_tracing", light);
  if (thin_lens) {
    traced_document = test::with_thin_lens(traced_document);
    path_traced_document = test::with_thin_lens(path_traced_document);
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
  const auto scene = test::scene_from_json(test::with_lamp_and_sky_groups(glass_block_scene("light_tracing", "area")));
  REQUIRE(scene->light_groups.size() == 2);
  const test::RenderedFilm rendered = test::render_xyz(*scene, 8, 3, 2, std::nullopt, nullptr, true);
  CHECK(rendered.statistics.caustic_light_tracing);
  const Film& film = *rendered.film;
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
  // light_tracing_scenes.h's hard case. Nothing may reach the film as NaN or infinity (the film would count and drop
  // such a splat; the REQUIRE sees any that got through), and the image is not black.
  nlohmann::json document = test::spot_in_glass_ball_scene();
  document["integrator"]["caustics"] = "light_tracing";
  const auto scene = test::scene_from_json(document);
  const test::RenderedFilm rendered = test::render_xyz(*scene, 16, 5);
  CHECK(rendered.statistics.caustic_light_tracing);
  CHECK(test::finite_total(*rendered.film) > 0.0);
}
