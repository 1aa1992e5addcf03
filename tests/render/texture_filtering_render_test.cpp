// Texture filtering through the renderer: the camera's ray differentials, a MIP-mapped checkerboard floor seen at
// grazing angles (its mean far away, its checks near by: no moiré), and the "filter" keys of the JSON format and of
// pbrt's imagemap.
#include <doctest/doctest.h>

#include <cmath>

#include "input_error_check.h"
#include "integration_support.h"
#include "render/camera/camera.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_image_files.h"

using namespace rimu;
using nlohmann::json;

namespace {

constexpr float kPiF = 3.14159265f;

Vec3 plane_hit(const Ray& ray, Vec3 point, Vec3 normal) {
  return ray.origin + ray.direction * (dot(normal, point - ray.origin) / dot(normal, ray.direction));
}

}  // namespace

TEST_CASE("camera differentials: one pixel's footprint on a plane facing the camera, pinhole, thin lens, orthographic") {
  const int width = 64, height = 48;
  const float depth = 3.0f;
  const Vec3 point{0, 0, depth}, normal{0, 0, -1};
  for (const float lens_radius : {0.0f, 0.05f}) {
    CAPTURE(lens_radius);
    CameraSettings settings;  // at the origin looking along +z
    settings.vertical_fov_deg = 40.0f;
    settings.lens_radius = lens_radius;
    settings.focus_distance = 2.0f;
    const Camera camera(settings, width, height);
    // A pixel's width at distance D: the film spans 2·D·tan(fov/2) over `height` pixels (square pixels). On a plane
    // parallel to the film every ray through one lens point meets it linearly in the film position, pinhole or not.
    const float pixel_m = 2.0f * depth * std::tan(20.0f * kPiF / 180.0f) / float(height);
    for (const float scale : {1.0f, 0.25f}) {
      for (const Vec2 film : {Vec2{32.0f, 24.0f}, Vec2{5.3f, 40.7f}}) {
        const Vec2 lens{0.8f, 0.3f};
        const Ray ray = camera.generate_ray(film.x, film.y, lens);
        const RayDifferentials d = camera.generate_differentials(ray, film.x, film.y, lens, scale);
        const Vec3 p = plane_hit(ray, point, normal);
        const SurfaceDifferentials s = surface_differentials(p, normal, {1, 0, 0}, {0, 1, 0}, d);
        CHECK(s.dpdx.x == doctest::Approx(scale * pixel_m).epsilon(1e-3));
        CHECK(s.dpdy.y == doctest::Approx(-scale * pixel_m).epsilon(1e-3));  // film y grows downwards
        CHECK(std::fabs(s.dpdx.y) < 1e-6f);
        // uv = (x, y) on this plane: the uv derivatives are the same numbers.
        CHECK(s.duvdx.x == doctest::Approx(s.dpdx.x).epsilon(1e-5));
        CHECK(s.duvdy.y == doctest::Approx(s.dpdy.y).epsilon(1e-5));
      }
    }
  }
  CameraSettings ortho;
  ortho.orthographic_height = 1.2f;
  const Camera camera(ortho, width, height);
  const Ray ray = camera.generate_ray(10.0f, 10.0f, {0.5f, 0.5f});
  const RayDifferentials d = camera.generate_differentials(ray, 10.0f, 10.0f, {0.5f, 0.5f}, 1.0f);
  const SurfaceDifferentials s = surface_differentials(plane_hit(ray, point, normal), normal, {1, 0, 0}, {0, 1, 0}, d);
  CHECK(s.dpdx.x == doctest::Approx(1.2f / float(height)).epsilon(1e-4));
}

TEST_CASE("camera differentials on a tilted plane equal the hits of the camera rays one pixel over") {
  CameraSettings settings;
  settings.camera_to_world = Transform::look_at({0.5f, 1.5f, -2.0f}, {0.0f, 0.0f, 1.0f}, {0, 1, 0});
  settings.vertical_fov_deg = 50.0f;
  const Camera camera(settings, 80, 60);
  const Vec3 point{0, 0, 0}, normal = normalize(Vec3{0.1f, 1.0f, -0.2f});
  for (const Vec2 film : {Vec2{40.0f, 30.0f}, Vec2{70.2f, 55.5f}, Vec2{3.0f, 41.0f}}) {
    const Ray ray = camera.generate_ray(film.x, film.y, {});
    const RayDifferentials d = camera.generate_differentials(ray, film.x, film.y, {}, 1.0f);
    const Vec3 p = plane_hit(ray, point, normal);
    const SurfaceDifferentials s = surface_differentials(p, normal, {1, 0, 0}, {0, 0, 1}, d);
    const Vec3 px = plane_hit(camera.generate_ray(film.x + 1.0f, film.y, {}), point, normal);
    const Vec3 py = plane_hit(camera.generate_ray(film.x, film.y + 1.0f, {}), point, normal);
    CHECK(length(s.dpdx - (px - p)) <= 1e-5f * length(px - p) + 1e-6f);
    CHECK(length(s.dpdy - (py - p)) <= 1e-5f * length(py - p) + 1e-6f);
  }
}

namespace {

// A floor 1 m under a level camera, 1000 m square, its uv repeating a 64×64 texel checkerboard (checks of 8 texels,
// linear values 0.2 and 0.8) every 2 m, lit only by a distant light (direct light only: max_depth 1). The horizon
// is the image's middle row; a row k pixels below it looks at the floor (k − ½)·0.94° down, at about
// 1/tan of that in metres.
json checker_floor(const std::string& image, const json& texture_extra) {
  json scene = json::parse(R"({
    "camera": {"from": [0, 1, 0], "to": [0, 1, 10], "vertical_fov_deg": 30},
    "film": {"resolution": [48, 32], "filter": {"type": "box"}},
    "integrator": {"max_depth": 1},
    "lights": [{"type": "distant", "direction": [0.3, 1, 0.2], "irradiance": 2}],
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-500, 0, -10], [-500, 0, 990], [500, 0, 990], [500, 0, -10]],
                "uvs": [[0, 0], [0, 500], [500, 500], [500, 0]]}]
  })");
  json texture = {{"texture", image}};
  texture.update(texture_extra);
  scene["materials"]["floor"] = {{"type", "diffuse"}, {"reflectance", texture}};
  return scene;
}

std::string checker_image() {
  std::vector<float> rgb;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const float v = ((x / 8 + y / 8) % 2) ? 0.8f : 0.2f;
      rgb.insert(rgb.end(), {v, v, v});
    }
  return test::write_pfm("mip_checker", 64, 64, rgb).string();
}

std::string grey_image() { return test::write_pfm("mip_checker_mean", 1, 1, {0.5f, 0.5f, 0.5f}).string(); }

std::vector<double> rows_of(const std::vector<double>& pixels, int width, int first_row, int last_row) {
  return {pixels.begin() + first_row * width, pixels.begin() + (last_row + 1) * width};
}

}  // namespace

TEST_CASE("MIP-mapped checkerboard at grazing angles: its mean far away without moiré, its checks near by") {
  constexpr int kSpp = 4, kWidth = 48;
  // The same sampler seed for the checker and for a uniform floor of the checker's mean (0.5): every sample draws
  // the same film position and wavelengths in both, so pixel by pixel they differ only by what the texture returns.
  const auto reference = test::render_xyz(*test::scene_from_json(checker_floor(grey_image(), json::object())), kSpp, 3);
  const std::vector<double> grey = test::luminance_values(*reference.film);
  for (const std::string filter : {"bilinear", "trilinear"}) {
    CAPTURE(filter);
    const auto rendered = test::render_xyz(*test::scene_from_json(checker_floor(checker_image(), {{"filter", filter}})), kSpp, 3);
    const std::vector<double> checker = test::luminance_values(*rendered.film);
    // Rows 17-23 see the floor 40 m to 7 m away: a pixel's sample footprint (½ pixel at 4 spp) spans ≥ 14 texels
    // in depth there, so the lookup reads level 4 or coarser (16-texel texels: whole pairs of checks), whose texels
    // are the mean. The pixels then equal the uniform floor's up to float rounding: no aliasing pattern at all.
    const std::vector<double> far_checker = rows_of(checker, kWidth, 17, 23), far_grey = rows_of(grey, kWidth, 17, 23);
    double worst = 0.0;
    for (size_t i = 0; i < far_grey.size(); ++i) {
      REQUIRE(far_grey[i] > 0.0);
      worst = std::max(worst, std::fabs(far_checker[i] / far_grey[i] - 1.0));
    }
    CHECK(worst < 1e-3);  // unfiltered, a pixel's 4 samples land on 0.2 or 0.8 checks: deviations of ±30 % and more
    const test::Estimate far = test::paired_difference(far_checker, far_grey);
    CHECK(std::fabs(far.mean) <= 3.0 * far.standard_error + 1e-4 * test::mean_of(far_grey));
    // Rows 29-31 see it 2.6-3.3 m away: footprints of ~3 texels read level 1-2, whose texels are still pure checks
    // (trilinear blends in some of the next level's, so its contrast is lower). The pixels there must keep the
    // pattern, ±60 % of the mean at full contrast: a lookup that always answered the mean would pass the test above
    // and give < 1e-3 here.
    const std::vector<double> near_checker = rows_of(checker, kWidth, 29, 31), near_grey = rows_of(grey, kWidth, 29, 31);
    double spread = 0.0;
    for (size_t i = 0; i < near_grey.size(); ++i) spread = std::max(spread, std::fabs(near_checker[i] / near_grey[i] - 1.0));
    CHECK(spread > 0.1);
  }
  // EWA keeps the checks across the line of sight (its ellipse is narrow there), so far pixels are not all the mean;
  // their block average is, within its standard error.
  const auto ewa = test::render_xyz(*test::scene_from_json(checker_floor(checker_image(), {{"filter", "ewa"}})), kSpp, 3);
  const std::vector<double> ewa_far = rows_of(test::luminance_values(*ewa.film), kWidth, 17, 23);
  const test::Estimate block = test::paired_difference(ewa_far, rows_of(grey, kWidth, 17, 23));
  CAPTURE(block.mean);
  CAPTURE(block.standard_error);
  CHECK(std::fabs(block.mean) <= 3.0 * block.standard_error + 1e-4 * test::mean_of(rows_of(grey, kWidth, 17, 23)));
}

TEST_CASE("texture filter keys: JSON \"filter\" and \"max_anisotropy\", and pbrt imagemap's \"filter\" and \"maxanisotropy\"") {
  const std::string image = grey_image();
  json scene = checker_floor(image, {{"filter", "ewa"}, {"max_anisotropy", 16}});
  // An image texture needs the footprint and so ∂p/∂u, ∂p/∂v (the uv derivatives solve against them); a plain
  // floor computes neither.
  const auto textured = test::scene_from_json(scene);
  CHECK(textured->texture_footprints);
  CHECK(textured->geometry.has_surface_tangents());
  CHECK(textured->transport_view().texture_footprints);
  json plain = checker_floor(image, json::object());
  plain["materials"]["floor"]["reflectance"] = 0.5;
  const auto untextured = test::scene_from_json(plain);
  CHECK_FALSE(untextured->texture_footprints);
  CHECK_FALSE(untextured->geometry.has_surface_tangents());
  CHECK_FALSE(untextured->transport_view().texture_footprints);
  test::input_error([&] { test::scene_from_json(checker_floor(image, {{"filter", "cubic"}})); },
                          {"/materials/floor/reflectance/filter", "cubic"});
  test::input_error([&] { test::scene_from_json(checker_floor(image, {{"max_anisotropy", 0.5}})); },
                          {"/materials/floor/reflectance/max_anisotropy"});

  test::ScratchFolder dir("pbrt_texture_filter");
  std::filesystem::copy_file(image, dir / "grey.pfm", std::filesystem::copy_options::overwrite_existing);
  const std::string header = "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  const PbrtImport imported = import_pbrt_text(
      header +
          "Texture \"a\" \"spectrum\" \"imagemap\" \"string filename\" \"grey.pfm\" \"string filter\" \"ewa\" \"float maxanisotropy\" 16\n"
          "Texture \"b\" \"spectrum\" \"imagemap\" \"string filename\" \"grey.pfm\" \"string filter\" \"trilinear\"\n"
          "Texture \"c\" \"spectrum\" \"imagemap\" \"string filename\" \"grey.pfm\"\n"
          "Texture \"d\" \"float\" \"imagemap\" \"string filename\" \"grey.pfm\" \"string filter\" \"point\"\n"
          "MakeNamedMaterial \"a\" \"string type\" \"diffuse\" \"texture reflectance\" \"a\"\n"
          "MakeNamedMaterial \"b\" \"string type\" \"diffuse\" \"texture reflectance\" \"b\"\n"
          "MakeNamedMaterial \"c\" \"string type\" \"diffuse\" \"texture reflectance\" \"c\"\n"
          "MakeNamedMaterial \"d\" \"string type\" \"conductor\" \"texture roughness\" \"d\"\n",
      "test.pbrt", dir.path, test::library());
  CHECK(imported.ignored.empty());
  const json& m = imported.document["materials"];
  CHECK(m["a"]["reflectance"]["filter"] == "ewa");
  CHECK(m["a"]["reflectance"]["max_anisotropy"] == 16.0);
  CHECK(m["b"]["reflectance"]["filter"] == "trilinear");
  CHECK_FALSE(m["c"]["reflectance"].contains("filter"));  // pbrt-v4's default, bilinear, is Rimu's
  CHECK(m["d"].dump().find("\"filter\":\"point\"") != std::string::npos);
}

TEST_CASE("MIP-mapped checkerboard seen through a medium: the volumetric integrator filters as the surface one does") {
  // The same floor with the camera inside a scene-wide, barely absorbing medium (σa = 10⁻⁶/m, no scattering), so the
  // volumetric path tracer renders it (lit by a point light): camera differentials reach the floor through the free flight unchanged, and
  // the far rows equal the uniform floor's (in the same medium) as without it. Point-sampled they deviate by ±30 %.
  constexpr int kSpp = 4, kWidth = 48;
  const auto in_medium = [](json scene) {
    scene["media"] = {{"air", {{"type", "homogeneous"}, {"sigma_a", 1e-6}, {"sigma_s", 0.0}, {"contains_camera", true}}}};
    // A scene-wide medium dims a light at infinity to nothing (its shadow rays are infinitely long): a point light
    // high above instead. Each pixel is compared with the same pixel of the uniform floor, so its falloff cancels.
    scene["lights"] = json::array({{{"type", "point"}, {"position", {0, 60, 25}}, {"intensity", 5000}}});
    return scene;
  };
  const auto reference = test::render_xyz(*test::scene_from_json(in_medium(checker_floor(grey_image(), json::object()))), kSpp, 3);
  const auto rendered =
      test::render_xyz(*test::scene_from_json(in_medium(checker_floor(checker_image(), {{"filter", "trilinear"}}))), kSpp, 3);
  const std::vector<double> far_checker = rows_of(test::luminance_values(*rendered.film), kWidth, 17, 23);
  const std::vector<double> far_grey = rows_of(test::luminance_values(*reference.film), kWidth, 17, 23);
  double worst = 0.0;
  for (size_t i = 0; i < far_grey.size(); ++i) {
    REQUIRE(far_grey[i] > 0.0);
    worst = std::max(worst, std::fabs(far_checker[i] / far_grey[i] - 1.0));
  }
  CHECK(worst < 1e-3);
}
