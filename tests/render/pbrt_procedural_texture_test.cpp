// pbrt-v4's procedural textures and texture mappings through the importer (docs/pbrt-import.md, "Texture"): each
// class becomes the Rimu texture of the same definition, placed by the Texture statement's transform, and a scene
// with them renders as its hand-written JSON twin.
#include <doctest/doctest.h>

#include <fstream>
#include <numbers>
#include <sstream>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/image/image_texture.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_image_files.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_procedural_texture_test {

// Mirrored header, as pbrt_texture_test.cpp's: pbrt's world is Rimu's (no x flip), the identity placement.
const std::string kHeader = "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

PbrtImport import_text(const std::string& text) {
  return import_pbrt_text(text, "test.pbrt", std::filesystem::temp_directory_path(), test::library());
}

TEST_CASE("pbrt procedural float textures: fbm, wrinkled, windy, dots and the 3D checkerboard, with their mappings") {
  const PbrtImport imported = import_text(
      kHeader +
      "Texture \"f\" \"float\" \"fbm\" \"integer octaves\" 5 \"float roughness\" 0.7\n"
      "Texture \"w\" \"float\" \"wrinkled\"\n"
      "AttributeBegin\nTranslate 1 2 3\n"
      "Texture \"v\" \"float\" \"windy\"\n"
      "Texture \"cube\" \"float\" \"checkerboard\" \"integer dimension\" 3 \"float tex1\" 0.1 \"float tex2\" 0.2\n"
      "Texture \"ball\" \"float\" \"dots\" \"string mapping\" \"spherical\" \"float inside\" 0.3\n"
      "Texture \"tube\" \"float\" \"checkerboard\" \"string mapping\" \"cylindrical\"\n"
      "Texture \"flat\" \"float\" \"dots\" \"string mapping\" \"planar\" \"vector3 v1\" [0 0 1] \"vector3 v2\" [1 0 0] "
      "\"float udelta\" 0.5 \"float vdelta\" 0.25\n"
      "AttributeEnd\n"
      "Texture \"uvdots\" \"float\" \"dots\" \"float uscale\" 4\n"
      "Texture \"all\" \"float\" \"mix\" \"texture tex1\" \"f\" \"texture tex2\" \"w\" \"texture amount\" \"v\"\n"
      "Texture \"shapes\" \"float\" \"mix\" \"texture tex1\" \"cube\" \"texture tex2\" \"ball\" \"texture amount\" \"tube\"\n"
      "MakeNamedMaterial \"a\" \"string type\" \"conductor\" \"texture roughness\" \"all\" \"bool remaproughness\" false\n"
      "MakeNamedMaterial \"b\" \"string type\" \"conductor\" \"texture roughness\" \"shapes\" \"bool remaproughness\" false\n"
      "MakeNamedMaterial \"c\" \"string type\" \"dielectric\" \"texture roughness\" \"flat\" \"bool remaproughness\" false\n"
      "MakeNamedMaterial \"d\" \"string type\" \"dielectric\" \"texture roughness\" \"uvdots\" \"bool remaproughness\" false\n");
  CHECK(imported.ignored.empty());
  const json& m = imported.document["materials"];
  const json placed = json::array({{{"matrix", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 1.0, 3.0}}}});
  const json f = {{"noise", "fbm"}, {"octaves", 5}, {"roughness", 0.7}};
  const json w = {{"noise", "wrinkled"}, {"octaves", 8}, {"roughness", 0.5}};  // pbrt's defaults
  const json v = {{"noise", "windy"}, {"transform", placed}};
  CHECK(m["a"]["roughness"] == json({{"power", {{{"mix", {f, w}}, {"amount", v}}, 0.5}}}));
  const json cube = {{"checkerboard", {0.1, 0.2}}, {"mapping", "solid"}, {"transform", placed}};
  // pbrt-v4 puts "inside" outside the dots and "outside" inside them (its Create swaps the two): imported as rendered.
  const json ball = {{"dots", {0.0, 0.3}}, {"mapping", "spherical"}, {"transform", placed}};
  const json tube = {{"checkerboard", {1.0, 0.0}}, {"mapping", "cylindrical"}, {"transform", placed}};
  CHECK(m["b"]["roughness"] == json({{"power", {{{"mix", {cube, ball}}, {"amount", tube}}, 0.5}}}));
  const json flat = {{"dots", {0.0, 1.0}}, {"mapping", "planar"}, {"transform", placed},
                     {"planar_axes", {{0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}}}, {"uv_offset", {0.5, 0.25}}};
  CHECK(m["c"]["roughness"] == json({{"power", {flat, 0.5}}}));
  CHECK(m["d"]["roughness"] == json({{"power", {{{"dots", {0.0, 1.0}}, {"uv_scale", {4.0, 1.0}}, {"uv_offset", {0.0, 0.0}}}, 0.5}}}));
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", std::filesystem::temp_directory_path(), test::library()));
}

TEST_CASE("pbrt procedural spectrum textures: marble, dots, 3D checkerboard, bad octaves and dimensions refused") {
  const PbrtImport imported = import_text(
      kHeader +
      "Texture \"stone\" \"spectrum\" \"marble\" \"float scale\" 3 \"float variation\" 0.4 \"integer octaves\" 6\n"
      "Texture \"spots\" \"spectrum\" \"dots\" \"texture inside\" \"stone\" \"rgb outside\" [0.1 0.2 0.3]\n"
      "Texture \"cubes\" \"spectrum\" \"checkerboard\" \"integer dimension\" 3 \"texture tex2\" \"spots\"\n"
      "MakeNamedMaterial \"a\" \"string type\" \"diffuse\" \"texture reflectance\" \"cubes\"\n");
  CHECK(imported.ignored.empty());
  const json stone = {{"noise", "marble"}, {"octaves", 6}, {"roughness", 0.5}, {"scale", 3.0}, {"variation", 0.4}};
  const json spots = {{"dots", {test::pbrt_rgb_reflectance(0.1, 0.2, 0.3), stone}}, {"uv_scale", {1.0, 1.0}}, {"uv_offset", {0.0, 0.0}}};
  CHECK(imported.document["materials"]["a"]["reflectance"] == json({{"checkerboard", {1.0, spots}}, {"mapping", "solid"}}));
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", std::filesystem::temp_directory_path(), test::library()));

  const auto refused = [](const std::string& texture, const std::string& message) {
    CHECK_THROWS_WITH_AS(import_text(kHeader + texture + "MakeNamedMaterial \"a\" \"string type\" \"conductor\" \"texture roughness\" \"t\"\n"),
                         doctest::Contains(message.c_str()), InputError);
  };
  refused("Texture \"t\" \"float\" \"fbm\" \"integer octaves\" -2\n", "test.pbrt:5");
  refused("Texture \"t\" \"float\" \"wrinkled\" \"integer octaves\" 31\n", "\"octaves\" must be 0-30");
  refused("Texture \"t\" \"float\" \"checkerboard\" \"integer dimension\" 4\n", "\"dimension\" must be 2 or 3");
  refused("Texture \"t\" \"float\" \"fbm\" \"float roughness\" 12\n", "\"roughness\" must be within");
}

TEST_CASE("JSON procedural textures: keys checked, mapping keys only where the mapping reads them") {
  const auto load = [](const json& roughness) {
    json scene = json::parse(R"({"camera": {"from": [0, 0, 5], "to": [0, 0, 0], "vertical_fov_deg": 30}, "shapes": []})");
    scene["materials"]["m"] = {{"type", "conductor"}, {"metal", "gold"}, {"roughness", roughness}};
    return load_scene(scene, "t.json", std::filesystem::temp_directory_path(), test::library());
  };
  CHECK_NOTHROW(load(json{{"noise", "fbm"}, {"octaves", 3}, {"transform", {{{"scale", 2}}}}}));
  CHECK_NOTHROW(load(json{{"checkerboard", {0.1, 0.2}}, {"mapping", "planar"}, {"planar_axes", {{1, 0, 0}, {0, 0, 1}}}}));
  CHECK_THROWS_WITH_AS(load(json{{"noise", "windy"}, {"octaves", 3}}), doctest::Contains("unknown key 'octaves'"), InputError);
  CHECK_THROWS_WITH_AS(load(json{{"noise", "perlin"}}), doctest::Contains("fbm"), InputError);
  CHECK_THROWS_WITH_AS(load(json{{"noise", "fbm"}, {"octaves", 40}}), doctest::Contains("octaves"), InputError);
  CHECK_THROWS_WITH_AS(load(json{{"noise", "fbm"}, {"roughness", 11}}), doctest::Contains("roughness"), InputError);
  CHECK_THROWS_WITH_AS(load(json{{"dots", {0.1, 0.2}}, {"mapping", "solid"}}), doctest::Contains("mapping"), InputError);
  CHECK_THROWS_WITH_AS(load(json{{"checkerboard", {0.1, 0.2}}, {"mapping", "spherical"}, {"uv_scale", {2, 2}}}),
                       doctest::Contains("unknown key 'uv_scale'"), InputError);
  CHECK_THROWS_WITH_AS(load(json{{"checkerboard", {0.1, 0.2}}, {"transform", {{{"scale", 2}}}}}),
                       doctest::Contains("unknown key 'transform'"), InputError);
}

TEST_CASE("pbrt marble ball and 3D-checkerboard block render as the same scene written in Rimu's JSON") {
  // cornell.pbrt with a marble ball (placed by the ball's own transform) and a block in 3D checks of 0.5 m, as
  // pbrt text and as a hand-written JSON twin; a twin whose marble is shifted by half a period (sin's
  // phase by π, t → 1 − t) must differ.
  const std::filesystem::path pbrt_file = test::test_data("pbrt/cornell.pbrt");
  std::stringstream text;
  text << std::ifstream(pbrt_file).rdbuf();
  std::string pbrt = text.str();
  const auto replace = [&pbrt](const std::string& from, const std::string& to) {
    REQUIRE(pbrt.find(from) != std::string::npos);
    pbrt.replace(pbrt.find(from), from.size(), to);
  };
  replace("NamedMaterial \"white\"\n  Translate 0.45 0.35 0.2\n  Scale 0.35 0.35 0.35\n",
          "Translate 0.45 0.35 0.2\n  Scale 0.35 0.35 0.35\n"
          "  Texture \"stone\" \"spectrum\" \"marble\" \"float scale\" 4 \"float variation\" 0.5\n"
          "  Material \"diffuse\" \"texture reflectance\" \"stone\"\n");
  // An instance's shapes keep the material of their ObjectBegin block (pbrt-v4); its textures read world points.
  replace("ObjectBegin \"block\"\n",
          "AttributeBegin\n  Scale 0.5 0.5 0.5\n"
          "  Texture \"checks\" \"spectrum\" \"checkerboard\" \"integer dimension\" 3 \"rgb tex1\" [0.6 0.05 0.05] \"rgb tex2\" [0.7 0.7 0.7]\n"
          "AttributeEnd\nObjectBegin \"block\"\n  Material \"diffuse\" \"texture reflectance\" \"checks\"\n");
  const PbrtImport imported = import_pbrt_text(pbrt, pbrt_file.string(), pbrt_file.parent_path(), test::library());
  CHECK(imported.ignored.empty());
  const auto from_pbrt = load_scene(imported.document, pbrt_file.string(), pbrt_file.parent_path(), test::library());

  std::ifstream in(test::test_data("pbrt/cornell_equivalent.json"));
  json twin = json::parse(in);
  // pbrt's texture spaces in Rimu's world: the ball's and block's CTMs, then the importer's mirror of x.
  const json mirror = {{"scale", {-1, 1, 1}}};
  const auto marble = [&](double y_shift) {
    return json{{"type", "diffuse"},
                {"reflectance", {{"noise", "marble"}, {"scale", 4}, {"variation", 0.5},
                                 {"transform", {{{"translate", {0, y_shift, 0}}}, {{"scale", 0.35}}, {{"translate", {0.45, 0.35, 0.2}}}, mirror}}}}};
  };
  twin["materials"]["stone"] = marble(0.0);
  const auto checks = [&](double x_shift) {
    return json{{"type", "diffuse"},
                {"reflectance", {{"checkerboard", {{{"rgb", {0.6, 0.05, 0.05}}}, {{"rgb", {0.7, 0.7, 0.7}}}}}, {"mapping", "solid"},
                                 {"transform", {{{"translate", {x_shift, 0, 0}}}, {{"scale", 0.5}}, mirror}}}}};
  };
  twin["materials"]["checks"] = checks(0.0);
  for (json& shape : twin["shapes"]) {
    if (shape["type"] == "sphere") shape["material"] = "stone";
  }
  twin["prototypes"]["block"][0]["material"] = "checks";
  const auto from_json = load_scene(twin, "cornell_equivalent.json", pbrt_file.parent_path(), test::library());
  const std::vector<double> a = test::luminance_values(*test::render_xyz(*from_pbrt, 128, 1).film);
  const std::vector<double> b = test::luminance_values(*test::render_xyz(*from_json, 128, 2).film);
  for (double deviation : test::block_deviations(a, b)) CHECK(deviation <= test::kSigmas);

  // The comparison can fail: the marble shifted by π/4 along texture y (after the scale of 4: a phase of π) and the
  // checks by one cube (red and white swapped).
  json shifted = twin;
  shifted["materials"]["stone"] = marble(std::numbers::pi / 4);
  shifted["materials"]["checks"] = checks(1.0);
  const auto other = load_scene(shifted, "shifted.json", pbrt_file.parent_path(), test::library());
  const std::vector<double> c = test::luminance_values(*test::render_xyz(*other, 128, 3).film);
  double worst = 0.0;
  for (double deviation : test::block_deviations(a, c)) worst = std::max(worst, deviation);
  CHECK(worst > test::kSigmas);
}

TEST_CASE("reflectance image scale and invert act on the texel RGB before upsampling (pbrt-v4's order)") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  const auto image = [](std::vector<float> rgb) { return std::make_shared<const RgbImage>(int(rgb.size() / 3), 1, std::move(rgb)); };
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 600.0f, 700.0f), Float4(1.0f));
  // scale 2, inverted: grey 0.3 → 1 − 0.6 = 0.4 (a flat spectrum); (0.6, 0.2, 0.1) → 1 − (1.2, 0.4, 0.2), clamped: (0, 0.6, 0.8).
  const ImageTexture scaled(image({0.3f, 0.3f, 0.3f, 0.6f, 0.2f, 0.1f}), upsampler, 2.0f, true);
  const ImageTexture expected(image({0.4f, 0.4f, 0.4f, 0.0f, 0.6f, 0.8f}), upsampler, 1.0f);
  for (const Vec2 uv : {Vec2{0.25f, 0.5f}, Vec2{0.75f, 0.5f}, Vec2{0.5f, 0.5f}}) {
    const SampledSpectrum a = scaled.evaluate(uv, lambda), b = expected.evaluate(uv, lambda);
    for (int lane = 0; lane < kLaneCount; ++lane) CHECK(a[lane] == doctest::Approx(b[lane]).epsilon(1e-4));
  }
  const SampledSpectrum grey = scaled.evaluate({0.25f, 0.5f}, lambda);
  for (int lane = 0; lane < kLaneCount; ++lane) CHECK(grey[lane] == doctest::Approx(0.4f).epsilon(0.01));
  // A scale above 1 brightens, up to white: 0.3 × 5 → 1.
  const SampledSpectrum white = ImageTexture(image({0.3f, 0.3f, 0.3f}), upsampler, 5.0f).evaluate({0.5f, 0.5f}, lambda);
  for (int lane = 0; lane < kLaneCount; ++lane) CHECK(white[lane] == doctest::Approx(1.0f).epsilon(1e-4));

  // The importer passes pbrt's scale (any) and invert through; an EXR's "encoding" is ignored, as pbrt-v4 does.
  test::ScratchFolder dir("pbrt_imagemap_scale");
  std::ofstream(dir / "paint.exr") << "not read";
  std::ofstream(dir / "paint.ppm") << "not read";
  const PbrtImport imported = import_pbrt_text(
      kHeader +
          "Texture \"bright\" \"spectrum\" \"imagemap\" \"string filename\" \"paint.ppm\" \"float scale\" 2.5 \"bool invert\" true\n"
          "Texture \"hdr\" \"spectrum\" \"imagemap\" \"string filename\" \"paint.exr\" \"string encoding\" \"sRGB\"\n"
          "MakeNamedMaterial \"a\" \"string type\" \"diffuse\" \"texture reflectance\" \"bright\"\n"
          "MakeNamedMaterial \"b\" \"string type\" \"diffuse\" \"texture reflectance\" \"hdr\"\n",
      "test.pbrt", dir.path, library);
  CHECK(imported.ignored.empty());
  const json& m = imported.document["materials"];
  CHECK(m["a"]["reflectance"]["scale"] == 2.5);
  CHECK(m["a"]["reflectance"]["invert"] == true);
  CHECK(m["b"]["reflectance"]["encoding"] == "linear");
}

TEST_CASE("pbrt coatedconductor with reflectance: the artist metal under the coat") {
  const PbrtImport imported = import_text(kHeader +
                                          "MakeNamedMaterial \"a\" \"string type\" \"coatedconductor\" \"rgb reflectance\" [0.9 0.6 0.2] "
                                          "\"float conductor.roughness\" 0.1\n");
  CHECK(imported.ignored.empty());
  const json& a = imported.document["materials"]["a"];
  CHECK(a["type"] == "coated_conductor");
  CHECK(a["reflectance"] == test::pbrt_rgb_reflectance(0.9, 0.6, 0.2));
  CHECK(!a.contains("metal"));
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", std::filesystem::temp_directory_path(), test::library()));
  CHECK_THROWS_WITH_AS(import_text(kHeader + "MakeNamedMaterial \"a\" \"string type\" \"coatedconductor\" \"rgb reflectance\" [0.9 0.6 0.2] "
                                             "\"spectrum conductor.eta\" \"metal-Au-eta\"\n"),
                       doctest::Contains("not both"), InputError);
}

}  // namespace pbrt_procedural_texture_test
