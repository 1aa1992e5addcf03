// Path guiding through the real render loop (render/renderer.h, transport/guiding/): the image mean with guiding
// equals the one without within the standard error (the Cornell box, the daylit room of data/scenes/interiors, the
// scene guiding is for, and two scenes with media), the field is trained in the first passes and its memory
// reported, and the same seed and thread count — or another thread count — give a bit-identical image.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "integration_support.h"
#include "render/scene/json_cursor.h"
#include "spectral/error.h"

using namespace rimu;
using namespace rimu::test;

namespace {

nlohmann::json small_version(const std::filesystem::path& path, int width, int height) {
  nlohmann::json document = parse_json_file(path);
  document["film"]["resolution"] = {width, height};
  document["film"]["filter"] = {{"type", "box"}};
  return document;
}

// `mode`: "on" (quadtrees), "mixture" (parallax-aware vMF mixtures) or "off".
std::unique_ptr<Scene> scene_with_guiding(nlohmann::json document, const std::filesystem::path& directory,
                                          const char* mode) {
  document["integrator"]["guiding"] = mode;
  return load_scene(document, "guiding_test.json", directory, library());
}

// Paired luminance difference of guided and unguided renders (different seeds: independent pixels) within
// kSigmas standard errors, and the guided render trained its field.
void check_unbiased(const nlohmann::json& document, const std::filesystem::path& path, int spp, const char* mode = "on") {
  const auto off = scene_with_guiding(document, path.parent_path(), "off");
  const auto on = scene_with_guiding(document, path.parent_path(), mode);
  const RenderedFilm unguided = render_xyz(*off, spp, 1);
  const RenderedFilm guided = render_xyz(*on, spp, 2);
  CHECK(!unguided.statistics.guiding.active);
  CHECK(guided.statistics.guiding.active);
  CHECK(guided.statistics.guiding.training_passes == 4);  // fitted after 1, 3, 7 and 15 samples; the pass of 16 is the last
  CHECK(guided.statistics.guiding.memory_bytes > 0);
  CHECK(guided.statistics.guiding.spatial_leaves >= 1);
  const std::vector<double> a = luminance_values(*guided.film), b = luminance_values(*unguided.film);
  const Estimate d = paired_difference(a, b);
  INFO(path.string() << ": guided − unguided = " << d.mean << " ± " << d.standard_error << " (mean " << mean_of(b) << ")");
  CHECK(std::fabs(d.mean) <= kSigmas * d.standard_error);
  CHECK(d.standard_error > 0.0);
}

void check_unbiased(const std::filesystem::path& path, int width, int height, int spp, const char* mode = "on") {
  check_unbiased(small_version(path, width, height), path, spp, mode);
}

// Pixels whose values are not bit-identical in `a` and `b`.
int differing_pixels(const RenderedFilm& a, const RenderedFilm& b) {
  const PixelBounds& bounds = a.film->pixel_bounds();
  int differing = 0;
  for (int y = bounds.y0; y < bounds.y1; ++y)
    for (int x = bounds.x0; x < bounds.x1; ++x) {
      const auto va = a.film->pixel_value(x, y), vb = b.film->pixel_value(x, y);
      if (std::memcmp(&va, &vb, sizeof va) != 0) ++differing;
    }
  return differing;
}

}  // namespace

TEST_CASE("path guiding is unbiased: the Cornell box") {
  check_unbiased(library().root() / "scenes" / "cornell_box" / "scene.json", 24, 24, 31);
}

TEST_CASE("path guiding is unbiased: the daylit room (sun and portal sky through a window)") {
  check_unbiased(library().root() / "scenes" / "interiors" / "daylit_room_open.json", 32, 18, 31);
}

TEST_CASE("path guiding with parallax-aware mixtures is unbiased: the Cornell box and the daylit room") {
  check_unbiased(library().root() / "scenes" / "cornell_box" / "scene.json", 24, 24, 31, "mixture");
  check_unbiased(library().root() / "scenes" / "interiors" / "daylit_room_open.json", 32, 18, 31, "mixture");
}

TEST_CASE("path guiding is unbiased in scenes with media: the Cornell box in haze, a cloud, a subsurface sphere") {
  // The volumetric integrator guides its surface vertices (walls, floors, the rough dielectric boundary of the skin
  // sphere: non-delta BSDFs) and leaves its medium vertices to the phase function. In the hazy Cornell box most
  // light reaches the walls by interreflection, so guided directions carry much of the image: a guided density
  // reported 0.8× its true value (a mutation) made its guided mean 12 % high, 4.6 standard errors, while the cloud,
  // lit mostly directly, moved by 0.7 % even at 160 × 120 and 64 spp.
  const std::filesystem::path cornell = library().root() / "scenes" / "cornell_box" / "scene.json";
  nlohmann::json hazy = small_version(cornell, 24, 24);
  hazy["media"] = {{"haze", {{"type", "homogeneous"}, {"sigma_a", 0.1}, {"sigma_s", 0.6}, {"contains_camera", true}}}};
  check_unbiased(hazy, cornell, 31);
  check_unbiased(hazy, cornell, 31, "mixture");
  check_unbiased(library().root() / "scenes" / "media" / "cloud.json", 24, 18, 31);
  check_unbiased(library().root() / "scenes" / "media" / "skin.json", 20, 20, 31);
}

TEST_CASE("path guiding is deterministic: the same seed gives a bit-identical image on 1 and 2 threads") {
  const std::filesystem::path path = library().root() / "scenes" / "interiors" / "daylit_room_open.json";
  for (const char* mode : {"on", "mixture"}) {  // the mixtures are fitted leaf by leaf in parallel
    CAPTURE(mode);
    const auto scene = scene_with_guiding(small_version(path, 24, 16), path.parent_path(), mode);
    const RenderedFilm one = render_xyz(*scene, 15, 5, 1);
    const RenderedFilm two = render_xyz(*scene, 15, 5, 2);
    const RenderedFilm again = render_xyz(*scene, 15, 5, 2);
    CHECK(one.statistics.guiding.training_passes == 3);
    CHECK(differing_pixels(one, two) == 0);
    CHECK(differing_pixels(two, again) == 0);
  }
  // And in a scene with media (the volumetric integrator's records, tile by tile as the surface integrator's).
  const std::filesystem::path cloud = library().root() / "scenes" / "media" / "cloud.json";
  const auto scene = scene_with_guiding(small_version(cloud, 24, 16), cloud.parent_path(), "on");
  const RenderedFilm one = render_xyz(*scene, 15, 5, 1);
  const RenderedFilm two = render_xyz(*scene, 15, 5, 2);
  CHECK(one.statistics.guiding.training_passes == 3);
  CHECK(one.statistics.guiding.spatial_leaves >= 1);
  CHECK(differing_pixels(one, two) == 0);
}

TEST_CASE("integrator.guiding takes on, off, mixture, true or false, anything else is an input error naming the key") {
  const std::filesystem::path path = library().root() / "scenes" / "cornell_box" / "scene.json";
  nlohmann::json document = small_version(path, 8, 8);
  for (const auto& [value, expected] : std::vector<std::pair<nlohmann::json, bool>>{
           {"on", true}, {"off", false}, {"mixture", true}, {true, true}, {false, false}}) {
    document["integrator"]["guiding"] = value;
    const auto scene = load_scene(document, "g.json", path.parent_path(), library());
    CHECK(scene->settings.integrator.guiding == expected);
    CHECK(scene->settings.integrator.guiding_mixture == (value == "mixture"));
  }
  document["integrator"]["guiding"] = "maybe";
  try {
    load_scene(document, "g.json", path.parent_path(), library());
    FAIL("loaded");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("guiding") != std::string::npos);
  }
}

TEST_CASE("path guiding pools its passes: a longer render fits more fields to a larger history, bit-identically") {
  // Fits after 1, 3, 7, 15, 31 (and 63) samples, each to every sample recorded so far: light found rarely is learned
  // from all of them, not from the last pass alone (docs/transport.md, "Path guiding", Training).
  const std::filesystem::path path = library().root() / "scenes" / "cornell_box" / "scene.json";
  const auto scene = scene_with_guiding(small_version(path, 16, 16), path.parent_path(), "on");
  const RenderedFilm shorter = render_xyz(*scene, 32, 3, 1);
  const RenderedFilm one = render_xyz(*scene, 64, 3, 1);
  const RenderedFilm two = render_xyz(*scene, 64, 3, 2);
  CHECK(shorter.statistics.guiding.training_passes == 5);
  CHECK(one.statistics.guiding.training_passes == 6);
  // 63 samples per pixel pooled against 31: about twice the history.
  CHECK(double(one.statistics.guiding.samples_recorded) > 1.8 * double(shorter.statistics.guiding.samples_recorded));
  CHECK(differing_pixels(one, two) == 0);
}
