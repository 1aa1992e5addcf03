// pbrt-v4 cameras and films beyond the perspective basics (docs/pbrt-import.md): crop windows and pixel bounds.
#include <doctest/doctest.h>

#include <OpenImageIO/imageio.h>
#include <fstream>
#include <sstream>

#include "input_error_check.h"
#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/camera/camera.h"
#include "render/render_job.h"
#include "pbrt_test_support.h"
#include "transport/sampling/equal_area_square.h"

using namespace rimu;
using nlohmann::json;

using namespace rimu::test::pbrt_t;

namespace {

// The message of loading a scene with this camera and no shapes, or "no error".
std::string camera_error(const json& camera) {
  try {
    test::scene_from_json({{"camera", camera}, {"shapes", json::array()}});
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}

}  // namespace

TEST_CASE("pbrt film: cropwindow becomes the film's crop_window, pixelbounds its crop, as pbrt-v4 reads them") {
  // cropwindow [x0 x1 y0 y1] (either order) stays fractions [x0, y0, x1, y1] (pixels ceil(res · value) at whatever
  // resolution renders; 10 × 8 → x 3-8, y 0-4, checked by the render below).
  const PbrtImport cropped = import_pbrt(test::test_data("pbrt/crop.pbrt"), test::library());
  CHECK(cropped.ignored.empty());
  CHECK(cropped.document["film"]["crop_window"] == json({0.25, 0.0, 0.75, 0.5}));
  CHECK_FALSE(cropped.document["film"].contains("crop"));
  // pixelbounds [x0 x1 y0 y1], clamped to the image (listed), and overridden by a cropwindow (listed).
  CHECK(import_text(kCamera + "Film \"rgb\" \"integer xresolution\" 10 \"integer yresolution\" 8 \"integer pixelbounds\" [1 4 2 6]\nWorldBegin\n")
            .document["film"]["crop"] == json({1, 2, 4, 6}));
  const PbrtImport clamped = import_text(kCamera + "Film \"rgb\" \"integer xresolution\" 10 \"integer yresolution\" 8 \"integer pixelbounds\" [-2 4 2 60]\nWorldBegin\n");
  CHECK(clamped.document["film"]["crop"] == json({0, 2, 4, 8}));
  REQUIRE(clamped.ignored.size() == 1);
  CHECK(clamped.ignored[0].what == "Film \"pixelbounds\" beyond the image (clamped, as in pbrt)");
  const PbrtImport both = import_text(kCamera + "Film \"rgb\" \"integer xresolution\" 10 \"integer yresolution\" 8 \"integer pixelbounds\" [1 4 2 6] \"float cropwindow\" [0 0.5 0 1]\nWorldBegin\n");
  CHECK(both.document["film"]["crop_window"] == json({0.0, 0.0, 0.5, 1.0}));
  CHECK_FALSE(both.document["film"].contains("crop"));
  CHECK(both.ignored.size() == 1);
  // The whole image is no crop at all.
  const json whole = import_text(kCamera + "Film \"rgb\" \"float cropwindow\" [0 1 0 1]\nWorldBegin\n").document["film"];
  CHECK_FALSE(whole.contains("crop"));
  CHECK_FALSE(whole.contains("crop_window"));
  // Empty or malformed windows are errors at the Film's line.
  CHECK(import_error(kCamera + "Film \"rgb\" \"float cropwindow\" [0.5 0.5 0 1]\nWorldBegin\n").find("t.pbrt:3: Film: the crop window or pixel bounds select no pixels") != std::string::npos);
  CHECK(import_error(kCamera + "Film \"rgb\" \"float cropwindow\" [0 0.5 0]\nWorldBegin\n").find("t.pbrt:3: Film: \"cropwindow\" takes 4 numbers") != std::string::npos);
}

TEST_CASE("scene film crop: rimu renders only the crop, and --crop overrides it") {
  const test::ScratchFolder folder("pbrt-crop");
  const auto data_window = [](const std::filesystem::path& exr) {
    auto in = OIIO::ImageInput::open(exr.string());
    REQUIRE(in);
    const OIIO::ImageSpec spec = in->spec();
    return std::array<int, 4>{spec.x, spec.y, spec.x + spec.width, spec.y + spec.height};
  };
  RenderJob job;
  job.scene = test::test_data("pbrt/crop.pbrt");
  job.exr_output = folder / "crop.exr";
  job.quiet = true;
  job.threads = 1;
  std::ostringstream log;
  run_render_job(job, log);
  CHECK(data_window(job.exr_output) == std::array<int, 4>{3, 0, 8, 4});
  job.crop = PixelBounds{0, 0, 2, 2};
  run_render_job(job, log);
  CHECK(data_window(job.exr_output) == std::array<int, 4>{0, 0, 2, 2});
  // The file's cropwindow is a fraction of the picture: at --resolution 5x5 it selects x ceil(1.25) = 2 to
  // ceil(3.75) = 4 and y 0 to ceil(2.5) = 3, as pbrt-v4 would at that resolution; at 40 × 32 x 10-30, y 0-16.
  job.crop.reset();
  job.width = 5;
  job.height = 5;
  run_render_job(job, log);
  CHECK(data_window(job.exr_output) == std::array<int, 4>{2, 0, 4, 3});
  job.width = 40;
  job.height = 32;
  run_render_job(job, log);
  CHECK(data_window(job.exr_output) == std::array<int, 4>{10, 0, 30, 16});
  // A window that selects no pixel at the resolution asked for names the scene's key: at 1 × 1 the x range is
  // ceil(0.25) = 1 to ceil(0.75) = 1.
  job.width = 1;
  job.height = 1;
  test::input_error([&] { run_render_job(job, log); }, {"/film/crop_window"});
}

TEST_CASE("scene film crop in pixels: a resolution that no longer holds it names the key") {
  const test::ScratchFolder folder("film-crop-pixels");
  const std::filesystem::path scene = folder / "s.pbrt";
  {
    std::ofstream out(scene);
    out << "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\n"
           "Film \"rgb\" \"integer xresolution\" 10 \"integer yresolution\" 8 \"integer pixelbounds\" [3 8 0 4]\n"
           "Sampler \"independent\" \"integer pixelsamples\" 1\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [1 1 1]\n";
  }
  RenderJob job;
  job.scene = scene;
  job.exr_output = folder / "out.exr";
  job.quiet = true;
  job.threads = 1;
  job.width = 5;
  job.height = 5;
  std::ostringstream log;
  test::input_error([&] { run_render_job(job, log); }, {"/film/crop"});
}

TEST_CASE("pbrt orthographic camera: the image is 2 camera units along the shorter axis, at any distance") {
  std::ifstream in(test::test_data("pbrt/orthographic.pbrt"));
  std::stringstream text;
  text << in.rdbuf();
  const PbrtImport imported = import_text(text.str());
  CHECK(imported.ignored.empty());
  CHECK(imported.document["camera"]["type"] == "orthographic");
  CHECK(imported.document["camera"]["height"] == 2.0);
  CHECK_FALSE(imported.document["camera"].contains("vertical_fov_deg"));
  // Portrait films: the shorter axis (the width) spans 2 units, so the height is 2·h/w.
  CHECK(import_text(kCamera.substr(0, kCamera.find("Camera")) + "Camera \"orthographic\"\nFilm \"rgb\" \"integer xresolution\" 10 \"integer yresolution\" 30\nWorldBegin\n")
            .document["camera"]["height"] == doctest::Approx(6.0));
  // Rendered: sky Y = 1 outside the disc, 0.5 on the sphere (a diffuse 0.5 under a uniform sky), so the image mean
  // is 1 − 0.5·π·5²/400 = 0.90183, from 3 units away and from 30. The disc edge's coverage, estimated by 64 samples
  // in each of ~31 edge pixels, has a standard error ≈ 0.5·√(31·0.25/64)/400 ≈ 2e-4; 3e-3 is 15 of them. A
  // perspective camera's disc would shrink 10 times from 3 to 30 units away.
  const double expected = 1.0 - 0.5 * M_PI * 25.0 / 400.0;
  for (const char* distance : {"-3", "-30"}) {
    CAPTURE(distance);
    std::string scene = text.str();
    scene.replace(scene.find("LookAt 0 0 -3"), 13, std::string("LookAt 0 0 ") + distance);
    const PbrtImport at = import_text(scene);
    const auto loaded = load_scene(at.document, "orthographic.pbrt", test::test_data("pbrt"), test::library());
    const test::Estimate y = test::estimate_of(test::luminance_values(*test::render_xyz(*loaded, 64, 3).film));
    CHECK(y.mean == doctest::Approx(expected).epsilon(3e-3));
  }
}

TEST_CASE("scene camera: orthographic rays are parallel, from the film plane, and the keys are checked") {
  CameraSettings settings;
  settings.camera_to_world = Transform::look_at({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
  settings.orthographic_height = 4.0f;
  const Camera camera(settings, 20, 10);  // 8 × 4 units
  const Ray corner = camera.generate_ray(0.0f, 0.0f, {0.5f, 0.5f});
  const Ray centre = camera.generate_ray(10.0f, 5.0f, {0.5f, 0.5f});
  CHECK(centre.origin.x == doctest::Approx(0.0));
  CHECK(centre.origin.y == doctest::Approx(0.0));
  CHECK(std::abs(corner.origin.x) == doctest::Approx(4.0));  // half the width: 4 units
  CHECK(corner.origin.y == doctest::Approx(2.0));             // top edge: +2
  CHECK(corner.direction.z == doctest::Approx(1.0));
  CHECK(centre.direction.z == doctest::Approx(1.0));
  CHECK(camera_error({{"type", "orthographic"}, {"from", {0, 0, 0}}, {"to", {0, 0, 1}}, {"height", 2}}) == "no error");
  CHECK(camera_error({{"type", "orthographic"}, {"from", {0, 0, 0}}, {"to", {0, 0, 1}}}).find("/camera") != std::string::npos);
  CHECK(camera_error({{"type", "orthographic"}, {"from", {0, 0, 0}}, {"to", {0, 0, 1}}, {"height", 2}, {"vertical_fov_deg", 30}})
            .find("no field of view") != std::string::npos);
  CHECK(camera_error({{"from", {0, 0, 0}}, {"to", {0, 0, 1}}, {"height", 2}}).find("orthographic") != std::string::npos);
}

TEST_CASE("scene camera: a spherical camera's directions, both mappings, its frame and its keys") {
  CameraSettings settings;
  settings.camera_to_world = Transform::look_at({1, 2, 3}, {1, 2, 4}, {0, 1, 0});  // camera axes = world axes
  const auto direction = [&](SphericalMapping mapping, float u, float v, int w, int h) {
    settings.spherical = mapping;
    const Camera camera(settings, w, h);
    const Ray ray = camera.generate_ray(u * float(w), v * float(h), {0.5f, 0.5f});
    CHECK(ray.origin.x == doctest::Approx(1.0));
    CHECK(ray.origin.z == doctest::Approx(3.0));
    return ray.direction;
  };
  const auto near = [](Vec3 a, Vec3 b) { return length(a - b) < 1e-5f; };
  // Image-right in the world: the look_at frame's x axis.
  const Vec3 right = Transform::look_at({1, 2, 3}, {1, 2, 4}, {0, 1, 0}).vector({1, 0, 0});
  using M = SphericalMapping;
  CHECK(near(direction(M::equirectangular, 0.5f, 0.5f, 64, 32), {0, 0, 1}));    // centre: the view axis
  CHECK(near(direction(M::equirectangular, 0.75f, 0.5f, 64, 32), right));       // a quarter turn to the right
  CHECK(near(direction(M::equirectangular, 0.0f, 0.5f, 64, 32), {0, 0, -1}));   // the left edge: behind
  CHECK(near(direction(M::equirectangular, 0.3f, 0.0f, 64, 32), {0, 1, 0}));    // the top row: up
  CHECK(near(direction(M::equirectangular, 0.3f, 1.0f, 64, 32), {0, -1, 0}));   // the bottom row: down
  CHECK(near(direction(M::equal_area_octahedral, 0.5f, 0.5f, 32, 32), {0, 0, 1}));
  CHECK(near(direction(M::equal_area_octahedral, 1.0f, 0.5f, 32, 32), right));
  CHECK(near(direction(M::equal_area_octahedral, 0.5f, 1.0f, 32, 32), {0, -1, 0}));
  CHECK(near(direction(M::equal_area_octahedral, 0.0f, 0.0f, 32, 32), {0, 0, -1}));
  // The frame turns the mapping in camera space: here its forward (z) is the camera's up.
  settings.spherical_frame = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
  CHECK(near(direction(M::equirectangular, 0.5f, 0.5f, 64, 32), {0, 1, 0}));
  settings.spherical_frame = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // Equal areas: the pixel centres of an equal-area image sample the sphere uniformly, so E[y²] = 1/3.
  {
    double mean_y2 = 0.0;
    settings.spherical = M::equal_area_octahedral;
    const Camera camera(settings, 64, 64);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const Vec3 d = camera.generate_ray(x + 0.5f, y + 0.5f, {0.5f, 0.5f}).direction;
        mean_y2 += double(d.y) * d.y / 4096.0;
      }
    CHECK(mean_y2 == doctest::Approx(1.0 / 3.0).epsilon(0.01));
  }
  const json base = {{"type", "spherical"}, {"from", {0, 0, 0}}, {"to", {0, 0, 1}}};
  CHECK(camera_error(base) == "no error");
  json with = base;
  with["mapping"] = "equal_area_octahedral";
  with["frame"] = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
  CHECK(camera_error(with) == "no error");
  with["frame"] = {{1, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  CHECK_CONTAINS(camera_error(with), "/camera/frame", "perpendicular");
  with = base;
  with["vertical_fov_deg"] = 30;
  CHECK_CONTAINS(camera_error(with), "/camera/vertical_fov_deg", "no 'vertical_fov_deg'");
  with = base;
  with["mapping"] = "mercator";
  CHECK_CONTAINS(camera_error(with), "/camera/mapping", "equirectangular");
  CHECK_CONTAINS(camera_error({{"from", {0, 0, 0}}, {"to", {0, 0, 1}}, {"mapping", "equirectangular"}}),
                 "/camera/mapping", "spherical");
}

TEST_CASE("pbrt spherical camera: a small light appears at the pixel pbrt-v4's mapping puts it") {
  // pbrt-v4 (SphericalCamera::GenerateRay): uv = pixel / resolution; equirectangular θ = π v, φ = 2π u,
  // (sin θ cos φ, sin θ sin φ, cos θ); equal-area EqualAreaSquareToSphere(uv); then y and z swapped. With
  // "LookAt 0 0 0  0 0 1  0 1 0" pbrt's camera space is its world space, so a light in world direction d is at
  // pbrt's (d.x, d.z, d.y) before the swap. The brightest pixel of Rimu's render of the imported scene must be the
  // one that holds it (the importer mirrors the world for its camera handedness: the test sees only the image).
  const Vec3 d = normalize(Vec3{1.0f, 0.5f, 2.0f});
  const std::string light = "AttributeBegin\nTranslate " + std::to_string(20 * d.x) + " " + std::to_string(20 * d.y) +
                            " " + std::to_string(20 * d.z) +
                            "\nAreaLightSource \"diffuse\" \"rgb L\" [100 100 100]\nShape \"sphere\" \"float radius\" 1\n"
                            "AttributeEnd\n";
  struct Case {
    std::string mapping;
    int width, height;
    Vec2 uv;  // pbrt's image position of d
  };
  const Vec3 pre_swap{d.x, d.z, d.y};
  float phi = std::atan2(pre_swap.y, pre_swap.x);
  if (phi < 0) phi += 2 * float(M_PI);
  const Vec2 equirect{phi / (2 * float(M_PI)), std::acos(pre_swap.z) / float(M_PI)};
  for (const Case& c : {Case{"equirectangular", 64, 32, equirect},
                        Case{"equalarea", 48, 48, equal_area_sphere_to_square(pre_swap)}}) {
    CAPTURE(c.mapping);
    const std::string text = "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"spherical\" \"string mapping\" \"" + c.mapping +
                             "\"\nFilm \"rgb\" \"integer xresolution\" " + std::to_string(c.width) +
                             " \"integer yresolution\" " + std::to_string(c.height) + "\nWorldBegin\n" + light;
    const PbrtImport imported = import_text(text);
    CHECK(imported.ignored.empty());
    const auto scene = load_scene(imported.document, "t.pbrt", test::test_data("pbrt"), test::library());
    const auto film = test::render_xyz(*scene, 16, 1).film;
    int best_x = -1, best_y = -1;
    double best = -1.0;
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x)
        if (film->pixel_value(x, y)[1] > best) best = film->pixel_value(x, y)[1], best_x = x, best_y = y;
    CAPTURE(best_x);
    CAPTURE(best_y);
    CHECK(std::abs(best_x + 0.5f - c.uv.x * c.width) <= 1.0f);
    CHECK(std::abs(best_y + 0.5f - c.uv.y * c.height) <= 1.0f);
  }
  CHECK_CONTAINS(import_error("LookAt 0 0 0  0 0 1  0 1 0\nCamera \"spherical\" \"string mapping\" \"cube\"\nWorldBegin\n"),
                 "t.pbrt:2", "\"equalarea\" or \"equirectangular\"");
}
