// Bidirectional path tracing (transport/integrators/bidirectional_path_integrator.h) through the real render loop:
// it must converge to the path tracer's image (the mean paired luminance difference, and every block's, within
// kSigmas standard errors) wherever the path tracer finds every path too: a floor lit through a glass block by an
// area light, a sphere light, through a thin lens; a coated floor (a delta and a non-delta lobe at one vertex) under
// a sky and a spot; the daylit rooms, whose light subpaths start as rays of daylight through the window. Where the
// path tracer cannot find a caustic (a spot through glass) it must agree with the path tracer plus light-traced
// caustics. Panes: two clear ones and two tinted ones over the floor, the glazed room; lamps inside lanterns. It is
// deterministic for any thread count, credits light groups, falls back to the path tracer where it cannot run, and
// writes nothing non-finite on hard cases.
#include <doctest/doctest.h>

#include <cmath>

#include "light_tracing_scenes.h"
#include "integration_support.h"
#include "render/scene/json_cursor.h"

using namespace rimu;

namespace {

nlohmann::json with_method(nlohmann::json scene, const char* method) {
  scene["integrator"]["method"] = method;
  return scene;
}

// `document` rendered bidirectionally (seed 2) against `reference_document` (seed 1, the path tracer unless it says
// otherwise): the mean paired difference and every 8 × 8 block's within kSigmas standard errors, and a standard
// error small enough to see a few per cent; in luminance, or in X, Y and Z where colour is what is tested.
void check_agrees(const nlohmann::json& document, const nlohmann::json& reference_document, int spp, int reference_spp,
                  const char* what, bool every_channel = false) {
  const auto bidirectional = test::scene_from_json(with_method(document, "bidirectional"));
  const auto reference = test::scene_from_json(reference_document);
  const test::RenderedFilm a = test::render_xyz(*bidirectional, spp, 2);
  const test::RenderedFilm b = test::render_xyz(*reference, reference_spp, 1);
  CHECK(a.statistics.bidirectional);
  CHECK_FALSE(b.statistics.bidirectional);
  for (int channel = every_channel ? 0 : 1; channel <= (every_channel ? 2 : 1); ++channel) {
    const std::vector<double> la = test::channel_values(*a.film, channel), lb = test::channel_values(*b.film, channel);
    const test::Estimate d = test::paired_difference(la, lb);
    const double m = test::mean_of(lb);
    INFO(std::string(what) << ", channel " << std::string(1, "XYZ"[channel]) << ": bidirectional − reference = " << d.mean << " ± "
                           << d.standard_error << " (mean " << m << ")");
    CHECK(d.standard_error > 0.0);
    CHECK(std::fabs(d.mean) <= test::kSigmas * d.standard_error);
    CHECK(d.standard_error < 0.02 * m);
    const std::vector<double> blocks = test::block_deviations(la, lb, a.film->width(), a.film->height(), 8);
    CHECK(test::worst_deviation(blocks) <= test::kSigmas);
  }
}

void check_agrees_with_path_tracer(const nlohmann::json& document, int spp, const char* what,
                                   bool every_channel = false) {
  check_agrees(document, document, spp, 2 * spp, what, every_channel);
}

// The glass block as a clear sheet: every path from the light to the floor passes two panes (its top and bottom).
nlohmann::json with_panes(nlohmann::json scene, const nlohmann::json& transmittance = nullptr) {
  scene["materials"]["glass"] = {{"type", "thin_dielectric"}, {"ior", 1.5}};
  if (!transmittance.is_null()) scene["materials"]["glass"]["transmittance"] = transmittance;
  return scene;
}

}  // namespace

TEST_CASE("bidirectional path tracing converges to the path tracer's image: area light, sphere light, thin lens") {
  check_agrees_with_path_tracer(test::glass_block_scene("area"), 128, "area light");
  check_agrees_with_path_tracer(test::glass_block_scene("sphere"), 384, "sphere light");
  check_agrees_with_path_tracer(test::with_thin_lens(test::glass_block_scene("area")), 128, "thin lens");
}

TEST_CASE("bidirectional path tracing: a spot's caustic through glass agrees with light-traced caustics") {
  // The path tracer never finds E D S S L from a spot; with caustics light-traced it does (its own test checks that
  // against the path tracer).
  nlohmann::json reference = test::glass_block_scene("spot");
  reference["integrator"]["caustics"] = "light_tracing";
  check_agrees(test::glass_block_scene("spot"), reference, 64, 128, "spot through glass");
}

TEST_CASE("bidirectional path tracing: a coated floor (delta and non-delta lobes at one vertex) under a sky and a spot") {
  // Where a camera path left a vertex by its delta lobe, that vertex can still be joined to by its non-delta one
  // (a first version skipped such joins and came out 12-25 % dark under a sky). An open scene: a coated floor, a
  // grey block and a glass ball on it, a sky and a spot.
  const nlohmann::json document = nlohmann::json::parse(R"({
    "camera": {"type": "pinhole", "from": [0.0, 0.8, -1.6], "to": [0.0, 0.1, 0.3], "up": [0, 1, 0],
               "vertical_fov_deg": 45},
    "film": {"resolution": [32, 24], "filter": {"type": "gaussian"}},
    "integrator": {"max_depth": 6},
    "materials": {"floor": {"type": "coated_diffuse", "reflectance": 0.6, "coat_ior": 1.5},
                  "grey": {"type": "diffuse", "reflectance": 0.5}, "glass": {"type": "dielectric", "ior": 1.5}},
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]},
      {"type": "box", "material": "grey", "min": [-0.7, 0.0, 0.2], "max": [-0.3, 0.4, 0.6]},
      {"type": "sphere", "material": "glass", "center": [0.35, 0.2, 0.2], "radius": 0.2}
    ],
    "lights": [{"type": "environment", "radiance": {"illuminant": "D65", "scale": 0.3}},
               {"type": "spot", "position": [0.6, 1.2, 0.0], "direction": [-0.3, -1.0, 0.2], "cone_angle_deg": 50,
                "intensity": {"illuminant": "D65", "scale": 1.0}}]
  })");
  nlohmann::json reference = document;
  reference["integrator"]["caustics"] = "light_tracing";
  check_agrees(document, reference, 64, 128, "coated floor");
}

TEST_CASE("bidirectional path tracing: light subpaths as rays of daylight through the daylit room's window") {
  // The glazed room's double glazing (a pane outside the portal, one inside) is passed by the daylight subpaths as
  // by shadow rays: before they passed it the room came out 34 % bright, and while panes were specular vertices to
  // every technique, 35 % dark.
  for (const char* file : {"daylit_room_open.json", "day_room_downlights.json", "daylit_room_glazed.json"}) {
    nlohmann::json document = parse_json_file(test::library().root() / "scenes" / "interiors" / file);
    document["film"]["resolution"] = {32, 18};
    document["integrator"]["daylit_points"] = false;  // the path tracer alone (the loader still builds the rays)
    const auto directory = test::library().root() / "scenes" / "interiors";
    const auto bidirectional = load_scene(with_method(document, "bidirectional"), file, directory, test::library());
    const auto path_traced = load_scene(document, file, directory, test::library());
    REQUIRE(bidirectional->daylight_rays);
    CHECK_FALSE(path_traced->daylight_rays);
    const test::RenderedFilm a = test::render_xyz(*bidirectional, 32, 2);
    const test::RenderedFilm b = test::render_xyz(*path_traced, 64, 1);
    CHECK(a.statistics.bidirectional);
    const std::vector<double> la = test::luminance_values(*a.film), lb = test::luminance_values(*b.film);
    const test::Estimate d = test::paired_difference(la, lb);
    INFO(std::string(file) << ": bidirectional − path traced = " << d.mean << " ± " << d.standard_error << " (mean "
              << test::mean_of(lb) << ")");
    CHECK(d.standard_error > 0.0);
    CHECK(std::fabs(d.mean) <= test::kSigmas * d.standard_error);
    CHECK(test::worst_deviation(test::block_deviations(la, lb, 32, 18, 8)) <= test::kSigmas);
  }
}

TEST_CASE("bidirectional path tracing passes panes as the path tracer does: two panes, a tinted pane, a spot") {
  // Subpaths pass a pane by its straight-through lobe and joins pass it as shadow rays do; the MIS weights count
  // the lobe choices on each edge from either side. Were a technique's density to miss them (or a pass to be a
  // vertex), the weights would not sum to one and the floor under the sheet would be off.
  check_agrees_with_path_tracer(with_panes(test::glass_block_scene("area")), 128, "area light through two panes");
  // A green glass (τₙ 0.2, 0.9, 0.5, 0.1 at 400, 500, 600, 700 nm): per lane, in X, Y and Z.
  const nlohmann::json green = {{"wavelengths_nm", {400, 500, 600, 700}}, {"values", {0.2, 0.9, 0.5, 0.1}}};
  check_agrees_with_path_tracer(with_panes(test::glass_block_scene("sphere"), green), 384,
                                "sphere light through two green panes", true);
  // A spot: light subpaths start through the panes. Light the sheet's faces reflect between them before it reaches
  // the floor is a caustic of a point light (E D S S L), which the path tracer never finds (it read 1.0 % dark,
  // 5.3 standard errors): the reference has caustics light-traced.
  nlohmann::json spot_reference = with_panes(test::glass_block_scene("spot"));
  spot_reference["integrator"]["caustics"] = "light_tracing";
  check_agrees(with_panes(test::glass_block_scene("spot")), spot_reference, 64, 128, "spot through two panes");
}

TEST_CASE("bidirectional path tracing: lamps inside diffusely transmitting lanterns (pbrt-v3's pavilion at night)") {
  // A point lamp and a small sphere lamp, each inside a closed paper box (diffuse transmission) on a floor under a
  // dim sky: all their light leaves through a surface that transmits diffusely, so light subpaths start with a
  // transmitting vertex and every join from outside meets the box's other side.
  const nlohmann::json document = nlohmann::json::parse(R"({
    "camera": {"type": "pinhole", "from": [0.0, 1.0, -2.2], "to": [0.0, 0.2, 0.3], "up": [0, 1, 0],
               "vertical_fov_deg": 45},
    "film": {"resolution": [32, 24], "filter": {"type": "gaussian"}},
    "integrator": {"max_depth": 6},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.6},
                  "paper": {"type": "diffuse_transmission", "reflectance": 0.3, "transmittance": 0.55},
                  "black": {"type": "diffuse", "reflectance": 0}},
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]},
      {"type": "box", "material": "paper", "min": [-0.7, 0.0, 0.0], "max": [-0.3, 0.5, 0.4]},
      {"type": "box", "material": "paper", "min": [0.3, 0.0, 0.0], "max": [0.7, 0.5, 0.4]},
      {"type": "sphere", "material": "black", "center": [0.5, 0.25, 0.2], "radius": 0.05,
       "emission": {"illuminant": "D65", "scale": 20.0}}
    ],
    "lights": [{"type": "point", "position": [-0.5, 0.25, 0.2], "spectrum": {"illuminant": "D65"},
                "luminous_power_lm": 0.5},
               {"type": "environment", "radiance": {"illuminant": "D65", "scale": 0.02}}]
  })");
  check_agrees_with_path_tracer(document, 128, "lanterns");
}

TEST_CASE("bidirectional path tracing gives the same image for any thread count") {
  const auto scene = test::scene_from_json(with_method(test::glass_block_scene("area"), "bidirectional"));
  const test::RenderedFilm one = test::render_xyz(*scene, 4, 7, 1);
  const test::RenderedFilm two = test::render_xyz(*scene, 4, 7, 2);
  CHECK(one.statistics.bidirectional);
  CHECK(test::film_bits(*one.film) == test::film_bits(*two.film));
}

TEST_CASE("bidirectional path tracing falls back to the path tracer where it cannot run") {
  // An orthographic camera: no light subpath can be joined to it.
  nlohmann::json orthographic = with_method(test::glass_block_scene("area"), "bidirectional");
  orthographic["camera"]["type"] = "orthographic";
  orthographic["camera"]["height"] = 1.5;
  orthographic["camera"].erase("vertical_fov_deg");
  CHECK_FALSE(test::render_xyz(*test::scene_from_json(orthographic), 1, 1).statistics.bidirectional);
}

TEST_CASE("bidirectional path tracing credits each contribution to its light's group: the layers sum to the beauty") {
  // The glass block under a square light (group "lamp") and a sky (group "sky"): every pixel's two layers sum to
  // its beauty, to float rounding (a sample's contributions are summed in float, into the beauty and into each
  // group: a sample here often has both lights' contributions, whose float sums round differently, ~1e-7 each),
  // and both have light (joins, splats and hits of each).
  const auto scene =
      test::scene_from_json(with_method(test::with_lamp_and_sky_groups(test::glass_block_scene("area")), "bidirectional"));
  REQUIRE(scene->light_groups.size() == 2);
  const test::RenderedFilm rendered = test::render_xyz(*scene, 8, 3, 2, std::nullopt, nullptr, true);
  CHECK(rendered.statistics.bidirectional);
  const Film& film = *rendered.film;
  double totals[2] = {0.0, 0.0}, worst = 0.0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const auto beauty = film.pixel_value(x, y);
      const auto a = film.group_value(x, y, 0), b = film.group_value(x, y, 1);
      for (int c = 0; c < 3; ++c) {
        const double sum = a[size_t(c)] + b[size_t(c)];
        worst = std::max(worst, std::fabs(sum - beauty[size_t(c)]) / std::max(1e-30, std::fabs(beauty[size_t(c)])));
      }
      totals[0] += a[1];
      totals[1] += b[1];
    }
  INFO("largest relative difference of the layers' sum from the beauty: " << worst);
  CHECK(worst < 1e-6);
  CHECK(totals[0] > 0.0);
  CHECK(totals[1] > 0.0);
}

TEST_CASE("bidirectional path tracing's hard cases write nothing non-finite") {
  // light_tracing_scenes.h's hard case (a spot inside a glass ball on a mirror, a 1 µm ball, a grazing camera) with
  // a rough glass slab and a rough coated wall: nothing non-finite may reach the film, and the image is not black.
  nlohmann::json document = test::spot_in_glass_ball_scene();
  document["integrator"]["method"] = "bidirectional";
  document["materials"]["wall"] = {{"type", "coated_diffuse"}, {"reflectance", 0.7}, {"roughness", 0.2}};
  document["materials"]["frosted"] = {{"type", "dielectric"}, {"ior", 1.5}, {"roughness", 0.3}};
  document["shapes"].push_back(
      {{"type", "box"}, {"material", "frosted"}, {"min", {-0.8, 0.0, 0.4}}, {"max", {-0.4, 0.5, 0.45}}});
  const auto scene = test::scene_from_json(document);
  const test::RenderedFilm rendered = test::render_xyz(*scene, 16, 5);
  CHECK(rendered.statistics.bidirectional);
  CHECK(test::finite_total(*rendered.film) > 0.0);
}
