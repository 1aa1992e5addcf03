// pbrt-v4 environment maps (docs/pbrt-import.md): an "infinite" light with "filename" is an equal-area octahedral
// image, read as Rimu's equal_area_octahedral environment in the light's frame. One bright texel must light a
// diffuse plane from the direction pbrt's mapping puts it; pbrt's "illuminance" normalisation is reproduced.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "transport/lights/area_light.h"
#include "transport/lights/projection_light.h"
#include "pbrt_test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

// The mean pixel luminance of `pbrt_text` (resolved in tests/data/pbrt) and its standard error.
test::Estimate plane_luminance(const std::string& pbrt_text) {
  const std::filesystem::path folder = test::test_data("pbrt");
  const PbrtImport imported = import_pbrt_text(pbrt_text, "envmap_texel.pbrt", folder, test::library());
  CHECK(imported.ignored.empty());
  const auto scene = load_scene(imported.document, "envmap_texel.pbrt", folder, test::library());
  return test::estimate_of(test::luminance_values(*test::render_xyz(*scene, 64, 5).film));
}

}  // namespace

using rimu::test::pbrt_t::import_error;  // the message of importing a text as t.pbrt, or "no error"

TEST_CASE("pbrt environment map: one bright texel lights a plane from the direction pbrt's mapping puts it") {
  // tests/data/pbrt/envmap_texel.pbrt: texel (17, 6) of a 32 × 32 map, its centre at light-space direction
  // (0.18061, −0.83023, 0.52734) by pbrt-v4's EqualAreaSquareToSphere (worked by hand in the .pbrt file), turned by
  // "Rotate -90 1 0 0" to world (0.18061, 0.52734, 0.83023). The plane's normal is (sin 45°, 0, cos 45°), so a
  // pixel shows Y = (0.5/π)·512·(4π/1024)·cos = cos, with cos = 0.71477 at the texel's centre; averaged over the
  // texel (a 200 × 200 midpoint rule of the same formulas) it is 0.71369, which is the expectation here.
  // Misreadings give other values: u mirrored 0.459, v mirrored 0 (the texel behind the plane), the light's
  // rotation ignored 0.501, u and v swapped 0.
  constexpr double kExpected = 0.71369;
  const std::string text = test::file_text(test::test_data("pbrt/envmap_texel.pbrt"));
  SUBCASE("pbrt's own camera handedness (the world is mirrored on import)") {
    const test::Estimate y = plane_luminance(text);
    CAPTURE(y.mean);
    CAPTURE(y.standard_error);
    CHECK(std::abs(y.mean - kExpected) <= test::kSigmas * y.standard_error + 2e-3 * kExpected);
  }
  SUBCASE("a camera whose handedness is Rimu's (no mirror)") {
    const test::Estimate y = plane_luminance("Scale -1 1 1\n" + text);
    CAPTURE(y.mean);
    CHECK(std::abs(y.mean - kExpected) <= test::kSigmas * y.standard_error + 2e-3 * kExpected);
  }
}

TEST_CASE("pbrt environment map: a map that is not square is read in pbrt-v3's equirectangular mapping") {
  // pbrt-v4 refuses such a map; pbrt-v3 (whose scenes hold them) looked light-space w up at u = φ/2π, v = θ/π with
  // φ = atan2(w.y, w.x) ∈ [0, 2π), θ = acos(w.z), v = 0 the top row. envmap_equirect.ppm is 16 × 8, black but
  // for texel (11, 2): φ ∈ [247.5°, 270°], θ ∈ [45°, 67.5°]. "Rotate -90 1 0 0" takes light (x, y, z) to world
  // (x, z, −y); the plane's normal, turned by "Rotate -34.27 1 0 0", is (0, 0.5631, 0.8264). A pixel of the plane
  // shows Y = (0.5/π)·scale·∫texel max(0, n·w) dω, integrated here by a 200 × 200 midpoint rule over the texel.
  // Misreadings give: u mirrored 0 (the texel behind the plane), v mirrored 0.37 of it, the rotation ignored ~0.
  constexpr double kScale = 50.0;
  constexpr int kSteps = 200;
  const double n[3] = {0.0, std::sin(34.27 * M_PI / 180), std::cos(34.27 * M_PI / 180)};
  double integral = 0.0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const double theta = M_PI / 8 * (2 + (i + 0.5) / kSteps), phi = 2 * M_PI / 16 * (11 + (j + 0.5) / kSteps);
      const double w[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      const double world[3] = {w[0], w[2], -w[1]};
      const double cosine = n[0] * world[0] + n[1] * world[1] + n[2] * world[2];
      integral += std::max(0.0, cosine) * std::sin(theta) * (M_PI / 8 / kSteps) * (2 * M_PI / 16 / kSteps);
    }
  const double expected = 0.5 / M_PI * kScale * integral;
  const std::filesystem::path folder = test::test_data("pbrt");
  const std::string text =
      "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16\n"
      "Integrator \"path\" \"integer maxdepth\" 1\nWorldBegin\n"
      "AttributeBegin\n  Rotate -90 1 0 0\n"
      "  LightSource \"infinite\" \"string filename\" \"envmap_equirect.ppm\" \"float scale\" 50\nAttributeEnd\n"
      "AttributeBegin\n  Rotate -34.27 1 0 0\n  Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
      "  Shape \"trianglemesh\" \"point3 P\" [-10 -10 0  10 -10 0  10 10 0  -10 10 0] \"integer indices\" [0 1 2  0 2 3]\n"
      "AttributeEnd\n";
  for (const std::string& prefix : {std::string(), std::string("Scale -1 1 1\n")}) {
    CAPTURE(prefix);
    const PbrtImport imported = import_pbrt_text(prefix + text, "t.pbrt", folder, test::library());
    REQUIRE(imported.ignored.size() == 1);  // listed: pbrt-v4 would refuse the map
    CHECK_CONTAINS(imported.ignored[0].what, "not square", "pbrt-v4 refuses it", "equirectangular");
    CHECK(imported.document["lights"][0]["mapping"] == "equirectangular");
    const auto scene = load_scene(imported.document, "t.pbrt", folder, test::library());
    const test::Estimate y = test::estimate_of(test::luminance_values(*test::render_xyz(*scene, 64, 5).film));
    CAPTURE(y.mean);
    CAPTURE(y.standard_error);
    CAPTURE(expected);
    CHECK(std::abs(y.mean - expected) <= test::kSigmas * y.standard_error + 2e-3 * expected);
  }
}

TEST_CASE("pbrt environment map: the JSON it becomes, illuminance, and errors") {
  const std::filesystem::path folder = test::test_data("pbrt");
  const std::string camera = "LookAt 0 0 5  0 0 0  0 1 0\nScale -1 1 1\nCamera \"perspective\"\nWorldBegin\n";
  SUBCASE("frame and mapping") {
    const PbrtImport imported = import_pbrt_text(
        camera + "Rotate -90 1 0 0\nLightSource \"infinite\" \"string filename\" \"envmap_texel.ppm\" \"float scale\" 3",
        "t.pbrt", folder, test::library());
    const json& light = imported.document["lights"][0];
    CHECK(light["mapping"] == "equal_area_octahedral");
    CHECK(light["scale"] == 3.0);
    const auto axis = [&](int i, int c) { return light["frame"][i][c].get<double>(); };
    CHECK(axis(0, 0) == doctest::Approx(1.0));
    CHECK(axis(1, 2) == doctest::Approx(-1.0));  // light y → world −z
    CHECK(axis(2, 1) == doctest::Approx(1.0));   // light z → world +y
  }
  SUBCASE("illuminance follows pbrt-v4's normalisation, k_e = (2π/N) Σ Y cos θ over the upper pixels") {
    // The one white texel is in the upper hemisphere at cos θ = z = 0.52734: k_e = 2π/1024 · 0.52734.
    const PbrtImport imported = import_pbrt_text(
        camera + "LightSource \"infinite\" \"string filename\" \"envmap_texel.ppm\" \"float illuminance\" 2",
        "t.pbrt", folder, test::library());
    CHECK(imported.document["lights"][0]["scale"].get<double>() ==
          doctest::Approx(2.0 / (2 * M_PI / 1024 * 0.52734375)).epsilon(1e-5));
  }
  SUBCASE("errors name the line") {
    const auto error = [&](const std::string& text) { return import_error(camera + text); };
    CHECK(error("LightSource \"infinite\" \"string filename\" \"nope.exr\"").find("t.pbrt:5: LightSource \"infinite\": cannot find the image") != std::string::npos);
    CHECK(error("LightSource \"infinite\" \"string filename\" \"envmap_texel.ppm\" \"rgb L\" [1 1 1]").find("t.pbrt:5: LightSource \"infinite\": give either \"L\" or \"filename\"") != std::string::npos);
  }
}

TEST_CASE("pbrt area light with an image: the emission it becomes, power, a sphere listed, and errors") {
  // A 2 × 2 m square of two triangles (pbrt: two shapes, each given "power") with envmap_texel.ppm: 32 × 32 pixels,
  // one white (Y = 1), so the image's mean luminance is 1/1024.
  const std::filesystem::path folder = test::test_data("pbrt");
  const std::string camera = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  const std::string square = "Shape \"trianglemesh\" \"point3 P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] "
                             "\"integer indices\" [0 1 2 0 2 3] \"point2 uv\" [0 0 1 0 1 1 0 1]\n";
  const auto import = [&](const std::string& light, const std::string& shape) {
    return import_pbrt_text(camera + "AttributeBegin\n" + light + "\n" + shape + "AttributeEnd\n", "t.pbrt", folder,
                            test::library());
  };
  SUBCASE("the image and its scale, in film units") {
    const PbrtImport imported =
        import(R"(AreaLightSource "diffuse" "string filename" "envmap_texel.ppm" "float scale" 3)", square);
    CHECK(imported.ignored.empty());
    const json& emission = imported.document["shapes"][0]["emission"];
    CHECK(emission["scale"] == 3.0);
    CHECK(emission["image"].get<std::string>().find("envmap_texel.ppm") != std::string::npos);
    const auto scene = load_scene(imported.document, "t.pbrt", folder, test::library());
    const auto& light = dynamic_cast<const AreaLight&>(*scene->lights[0]);
    CHECK(light.is_textured());
  }
  SUBCASE("power: pbrt-v4's k_e = π A · mean pixel luminance, per shape") {
    // Each triangle (A = 2 m²) is given power 5: scale = 5 / (π · 2 · 1/1024) on each, the mesh's 2 · 5 over 4 m².
    const PbrtImport imported =
        import(R"(AreaLightSource "diffuse" "string filename" "envmap_texel.ppm" "float power" 5)", square);
    CHECK(imported.document["shapes"][0]["emission"]["scale"].get<double>() ==
          doctest::Approx(5.0 / (M_PI * 2.0 / 1024.0)).epsilon(1e-6));
  }
  SUBCASE("on a sphere: the tessellated sphere (pbrt's uv) with the image") {
    const PbrtImport imported =
        import(R"(AreaLightSource "diffuse" "string filename" "envmap_texel.ppm")", "Shape \"sphere\" \"float radius\" 1\n");
    CHECK(imported.ignored.empty());
    const json& shape = imported.document["shapes"][0];
    CHECK(shape["type"] == "triangles");
    CHECK(shape["emission"].contains("image"));
  }
  SUBCASE("errors name the line") {
    const auto error = [&](const std::string& light) {
      return import_error(camera + light + "\n" + square);
    };
    CHECK(error(R"(AreaLightSource "diffuse" "string filename" "nope.png")").find("t.pbrt:4: AreaLightSource \"diffuse\": cannot find the image") != std::string::npos);
    CHECK(error(R"(AreaLightSource "diffuse" "string filename" "envmap_texel.ppm" "rgb L" [1 1 1])").find("t.pbrt:4: AreaLightSource \"diffuse\": give either \"L\" or \"filename\"") != std::string::npos);
  }
}

TEST_CASE("pbrt projection light: frame, field, the pixel each direction gets, intensity and power") {
  // envmap_texel.ppm: 32 × 32, one white pixel at (17, 6). pbrt-v4 projects along light-space +z through a screen of
  // [−1, 1]² at tan(fov/2), light-space +x to the image's right and +y to its top row (its flip of y). A camera
  // whose handedness is Rimu's (Scale −1 1 1), so light space is world space here.
  const std::filesystem::path folder = test::test_data("pbrt");
  const std::string camera = "LookAt 0 0 5  0 0 0  0 1 0\nScale -1 1 1\nCamera \"perspective\"\nWorldBegin\n";
  const double nits_per_unit = SpectralResponse::from_spec(test::library(), "xyz").luminance_nits_per_unit_y();
  const PbrtImport imported = import_pbrt_text(
      camera + "LightSource \"projection\" \"string filename\" \"envmap_texel.ppm\" \"float fov\" 40 \"float scale\" 2",
      "t.pbrt", folder, test::library());
  CHECK(imported.ignored.empty());
  const json& light = imported.document["lights"][0];
  CHECK(light["type"] == "projection");
  CHECK(light["fov_deg"] == 40.0);
  CHECK(light["white_intensity_cd"].get<double>() == doctest::Approx(2.0 * nits_per_unit));
  const auto scene = load_scene(imported.document, "t.pbrt", folder, test::library());
  const auto& projector = dynamic_cast<const ProjectionLight&>(*scene->lights[0]);
  const double t = std::tan(20.0 * M_PI / 180.0);
  const double sx = -1.0 + 2.0 * 17.5 / 32.0, sy = 1.0 - 2.0 * 6.5 / 32.0;  // the white pixel's centre on the screen
  const Vec3 towards = normalize(Vec3{float(sx * t), float(sy * t), 1.0f});
  CHECK(projector.pixel_towards(towards) == std::pair<int, int>{17, 6});
  CHECK(projector.pixel_towards(normalize(Vec3{float(sx * t), float(-sy * t), 1.0f})) == std::pair<int, int>{17, 25});
  SUBCASE("power: luminous_power_lm = pbrt's power in the same film units") {
    const PbrtImport powered = import_pbrt_text(
        camera + "LightSource \"projection\" \"string filename\" \"envmap_texel.ppm\" \"float power\" 3",
        "t.pbrt", folder, test::library());
    CHECK(powered.document["lights"][0]["luminous_power_lm"].get<double>() == doctest::Approx(3.0 * nits_per_unit));
  }
  SUBCASE("errors name the line") {
    CHECK(import_error(camera + "LightSource \"projection\"").find("t.pbrt:5: LightSource \"projection\": \"filename\" is required") != std::string::npos);
  }
}

TEST_CASE("pbrt infinite light portal: four world-space points become the environment's portal") {
  const std::filesystem::path folder = test::test_data("pbrt");
  const std::string camera = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  const std::string portal = " \"point3 portal\" [4 1 -1  4 1 1  4 2 1  4 2 -1]";
  // pbrt-v4 reads the portal in world space: the current transform (a rotation here) does not apply to it.
  for (const std::string source : {"\"rgb L\" [0.5 0.5 0.5]", "\"string filename\" \"envmap_texel.ppm\""}) {
    CAPTURE(source);
    const PbrtImport imported =
        import_pbrt_text(camera + "Rotate 90 0 1 0\nLightSource \"infinite\" " + source + portal, "t.pbrt", folder, test::library());
    const json& light = imported.document["lights"][0];
    REQUIRE(light.contains("portals"));
    CHECK(light["portals"] == json::parse("[[[4, 1, -1], [4, 1, 1], [4, 2, 1], [4, 2, -1]]]"));
    for (const auto& ignored : imported.ignored) CHECK(ignored.what.find("portal") == std::string::npos);
    // The document loads: the portal reaches the light.
    CHECK(load_scene(imported.document, "t.json", folder, test::library())->lights.size() == 1);
  }
  const auto error = [&](const std::string& text) { return import_error(camera + text); };
  CHECK(error("LightSource \"infinite\" \"point3 portal\" [4 1 -1  4 1 1  4 2 1]").find("t.pbrt:4: LightSource \"infinite\": \"portal\" takes four points, not 3") != std::string::npos);
  CHECK(error("LightSource \"infinite\" \"point3 portal\" [4 1 -1  4 1 1  4 2 2  4 2 -1]").find("t.pbrt:4: LightSource \"infinite\": the four \"portal\" points must form a rectangle") != std::string::npos);
}
