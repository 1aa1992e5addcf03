// Normal and bump maps through the whole renderer: a diffuse floor under a distant light is as bright as the cosine
// between the light and the MAPPED normal predicts, for a constant tilted normal map and for the bump map of a
// linear ramp with the same tilt; and surface tangents are computed only for scenes that have such a map.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_image_files.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace normal_map_render_test {

using rimu::test::kPi;
constexpr double kLightDeg = 40.0;  // the light's angle from the floor's normal, towards +x
constexpr double kTiltDeg = 20.0;

// A 4 m floor (u along +x, v along +z: ∂p/∂u = (4, 0, 0)) seen from above, lit only by a delta distant light:
// every pixel sees ρ/π · E · cos(light, shading normal), with nothing else in the scene to bounce from.
json floor_scene(const json& floor_material) {
  const double a = kLightDeg * kPi / 180.0;
  json scene = json::parse(R"({
    "camera": {"from": [0, 3, -1], "to": [0, 0, 0], "vertical_fov_deg": 30},
    "film": {"resolution": [16, 16], "filter": {"type": "box"}},
    "integrator": {"max_depth": 4},
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]],
       "uvs": [[0, 0], [0, 1], [1, 1], [1, 0]]}
    ]
  })");
  scene["lights"] = json::array({{{"type", "distant"}, {"direction", {std::sin(a), std::cos(a), 0.0}}, {"irradiance", 2.0}}});
  scene["materials"]["floor"] = floor_material;
  return scene;
}

double mean_luminance(const json& scene) {
  return test::mean_of(test::luminance_values(*test::render_xyz(*test::scene_from_json(scene), 4, 15).film));
}

// A 1×1 linear-float normal map of the tangent-space vector (sin t, 0, cos t) encoded as rgb = (n + 1)/2.
std::string tilted_normal_map(const std::string& name, double tilt_rad) {
  const float r = float(0.5 * (std::sin(tilt_rad) + 1.0)), b = float(0.5 * (std::cos(tilt_rad) + 1.0));
  return test::write_pfm(name, 1, 1, {r, 0.5f, b}).string();
}

// A 64×1 linear ramp 0 … 1 (texel i = i/63): between the first and last texel centres d(u) = (64/63)·(u − 1/128).
std::string ramp_image() {
  std::vector<float> rgb;
  for (int i = 0; i < 64; ++i)
    for (int c = 0; c < 3; ++c) rgb.push_back(float(i) / 63.0f);
  return test::write_pfm("bump_ramp", 64, 1, rgb).string();
}

TEST_CASE("normal map render: a constant tilted map scales a floor's brightness by cos(θ ∓ tilt)/cos θ") {
  const json plain = {{"type", "diffuse"}, {"reflectance", 0.5}};
  const double reference = mean_luminance(floor_scene(plain));
  REQUIRE(reference > 0.0);
  const double light = kLightDeg * kPi / 180.0, tilt = kTiltDeg * kPi / 180.0;
  // The map's x is ∂p/∂u = +x: a positive tilt leans the normal towards the light.
  for (const double signed_tilt : {tilt, -tilt}) {
    json mapped = plain;
    mapped["normal_map"] = tilted_normal_map(signed_tilt > 0 ? "nmap_toward" : "nmap_away", signed_tilt);
    const double ratio = mean_luminance(floor_scene(mapped)) / reference;
    // The two renders use the same sample points and wavelengths (same seed, same sample dimensions): the ratio
    // has no noise of its own, only float rounding, so 0.1 % is far from both it and a wrong frame (≥ 20 %).
    CHECK(ratio == doctest::Approx(std::cos(light - signed_tilt) / std::cos(light)).epsilon(1e-3));
  }
  // A flat map (rgb 0.5, 0.5, 1) changes nothing.
  json flat = plain;
  flat["normal_map"] = tilted_normal_map("nmap_flat", 0.0);
  CHECK(mean_luminance(floor_scene(flat)) / reference == doctest::Approx(1.0).epsilon(1e-4));
}

TEST_CASE("normal map render: an 8-bit map is read linearly unless the scene asks for the sRGB curve") {
  // One texel, the sRGB codes of (n + 1)/2 for n tilted 20° away from the light: (155, 188, 252). sRGB-decoded,
  // n = (−0.344, 0.006, 0.947), and the floor darkens to ≈ cos 60°/cos 40° = 0.653; read as v/255 (the default),
  // n = (0.216, 0.475, 0.976) leans towards the light instead (1.046).
  const std::vector<uint8_t> codes = {155, 188, 252};
  const std::string file = test::write_ppm("nmap_8bit", 1, 1, codes).string();
  const auto linear = [](uint8_t c) { return c / 255.0; };
  const auto srgb = [](uint8_t c) {  // IEC 61966-2-1
    const double v = c / 255.0;
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  const double light = kLightDeg * kPi / 180.0;
  // The map's x is ∂p/∂u = +x (towards the light), its z the floor's normal; its y lies across the light's plane.
  const auto expected_ratio = [&](auto decode) {
    const double x = 2 * decode(codes[0]) - 1, y = 2 * decode(codes[1]) - 1, z = 2 * decode(codes[2]) - 1;
    return (x * std::sin(light) + z * std::cos(light)) / std::sqrt(x * x + y * y + z * z) / std::cos(light);
  };
  const json plain = {{"type", "diffuse"}, {"reflectance", 0.5}};
  const double reference = mean_luminance(floor_scene(plain));
  const auto ratio = [&](const json& normal_map) {
    json mapped = plain;
    mapped["normal_map"] = normal_map;
    return mean_luminance(floor_scene(mapped)) / reference;
  };
  // As in the tilted-map test, the renders share their samples: 0.1 % is rounding, and the two decodings differ by 60 %.
  CHECK(ratio(file) == doctest::Approx(expected_ratio(linear)).epsilon(1e-3));
  CHECK(ratio({{"image", file}, {"encoding", "linear"}}) == doctest::Approx(expected_ratio(linear)).epsilon(1e-3));
  CHECK(ratio({{"image", file}, {"encoding", "srgb"}}) == doctest::Approx(expected_ratio(srgb)).epsilon(1e-3));
  // Bad forms name the key.
  const auto load = [&](const json& normal_map) {
    json mapped = plain;
    mapped["normal_map"] = normal_map;
    return test::scene_from_json(floor_scene(mapped));
  };
  CHECK_THROWS_WITH_AS(load({{"image", file}, {"encoding", "gamma"}}), doctest::Contains("normal_map/encoding"), InputError);
  CHECK_THROWS_WITH_AS(load({{"file", file}}), doctest::Contains("normal_map"), InputError);
  CHECK_THROWS_WITH_AS(load(3), doctest::Contains("normal_map"), InputError);
}

TEST_CASE("bump map render: a linear ramp displacement of slope tan(tilt) renders as the same tilt") {
  const json plain = {{"type", "diffuse"}, {"reflectance", 0.5}};
  const double reference = mean_luminance(floor_scene(plain));
  const double light = kLightDeg * kPi / 180.0, tilt = kTiltDeg * kPi / 180.0;
  // Height along +y rising with x by tan(tilt) per metre: d(u) = scale·(64/63)·u + c and x = 4u, so
  // scale = 4·tan(tilt)·63/64. A rise towards +x leans the normal away from the light (−x); a fall, towards it.
  const double scale = 4.0 * std::tan(tilt) * 63.0 / 64.0;
  for (const double sign : {1.0, -1.0}) {
    json bumped = plain;
    bumped["displacement"] = {{"texture", ramp_image()}, {"encoding", "linear"}, {"scale", sign * scale}};
    const double ratio = mean_luminance(floor_scene(bumped)) / reference;
    CHECK(ratio == doctest::Approx(std::cos(light + sign * tilt) / std::cos(light)).epsilon(1e-3));
  }
}

TEST_CASE("surface tangents: computed only when some material of the scene has a normal or bump map") {
  const json plain = {{"type", "diffuse"}, {"reflectance", 0.5}};
  CHECK_FALSE(test::scene_from_json(floor_scene(plain))->geometry.has_surface_tangents());
  json mapped = plain;
  mapped["normal_map"] = tilted_normal_map("nmap_tangents", 0.3);
  CHECK(test::scene_from_json(floor_scene(mapped))->geometry.has_surface_tangents());
  json bumped = plain;
  bumped["displacement"] = 0.1;
  CHECK(test::scene_from_json(floor_scene(bumped))->geometry.has_surface_tangents());
  // Through a mix: the chosen material's map needs them.
  json mix_scene = floor_scene({{"type", "mix"}, {"materials", {"plain", "mapped"}}, {"amount", 0.5}});
  mix_scene["materials"]["plain"] = plain;
  mix_scene["materials"]["mapped"] = mapped;
  CHECK(test::scene_from_json(mix_scene)->geometry.has_surface_tangents());
}

TEST_CASE("normal map: bad input names the key") {
  json both = {{"type", "diffuse"}, {"reflectance", 0.5}, {"normal_map", tilted_normal_map("nmap_both", 0.1)},
               {"displacement", 0.1}};
  CHECK_THROWS_WITH_AS(test::scene_from_json(floor_scene(both)), doctest::Contains("not both"), InputError);
  json missing = {{"type", "diffuse"}, {"reflectance", 0.5}, {"normal_map", "/nonexistent/normal.png"}};
  CHECK_THROWS_WITH_AS(test::scene_from_json(floor_scene(missing)), doctest::Contains("normal_map"), InputError);
}

TEST_CASE("pbrt normalmap and displacement: imported as the material's normal_map and displacement") {
  test::ScratchFolder dir("pbrt_normal_maps");
  std::filesystem::copy_file(tilted_normal_map("pbrt_nmap", 0.2), dir / "normals.pfm",
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(test::write_ppm("pbrt_nmap_8bit", 1, 1, {188, 188, 255}), dir / "normals.ppm",
                             std::filesystem::copy_options::overwrite_existing);
  const std::string header = "LookAt 0 3 -1  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  const PbrtImport imported = import_pbrt_text(
      header +
          "Texture \"bumps\" \"float\" \"checkerboard\" \"float uscale\" 8 \"float vscale\" 8 \"float tex2\" 0.01\n"
          "MakeNamedMaterial \"mapped\" \"string type\" \"diffuse\" \"string normalmap\" \"normals.pfm\"\n"
          "MakeNamedMaterial \"bumped\" \"string type\" \"conductor\" \"texture displacement\" \"bumps\"\n"
          "MakeNamedMaterial \"both\" \"string type\" \"diffuse\" \"string normalmap\" \"normals.pfm\" \"float displacement\" 0.1\n"
          "MakeNamedMaterial \"stb\" \"string type\" \"diffuse\" \"string normalmap\" \"normals.ppm\"\n"
          "NamedMaterial \"mapped\"\n"
          "Shape \"bilinearmesh\" \"point3 P\" [-1 0 -1  1 0 -1  -1 0 1  1 0 1] \"point2 uv\" [0 0 1 0 0 1 1 1]\n",
      "test.pbrt", dir.path, test::library());
  const json& m = imported.document["materials"];
  CHECK(m["mapped"]["normal_map"].get<std::string>().find("normals.pfm") != std::string::npos);
  CHECK_FALSE(m["mapped"].contains("displacement"));
  // pbrt-v4 reads normal maps asking for linear values, which only its PNG reader honours (a float file is linear
  // anyway): a PPM (like a TGA, JPEG or BMP) is sRGB-decoded by its stb_image path, and is imported so.
  CHECK(m["stb"]["normal_map"]["image"].get<std::string>().find("normals.ppm") != std::string::npos);
  CHECK(m["stb"]["normal_map"]["encoding"] == "srgb");
  CHECK(m["bumped"]["displacement"]["checkerboard"] == json({1.0, 0.01}));  // pbrt's default tex1 is 1
  CHECK(m["both"].contains("normal_map"));
  CHECK_FALSE(m["both"].contains("displacement"));
  // Only the displacement next to a normal map is reported.
  REQUIRE(imported.ignored.size() == 1);
  CHECK(imported.ignored[0].what.find("displacement") != std::string::npos);
  const auto scene = load_scene(imported.document, "test.pbrt", dir.path, test::library());
  CHECK(scene->geometry.has_surface_tangents());
  // A PNG normal map stays linear, as pbrt-v4's PNG reader is asked (only the file's presence is checked here).
  std::filesystem::copy_file(dir / "normals.ppm", dir / "normals.png", std::filesystem::copy_options::overwrite_existing);
  const PbrtImport png = import_pbrt_text(header + "MakeNamedMaterial \"png\" \"string type\" \"diffuse\" \"string normalmap\" \"normals.png\"\n",
                                          "test.pbrt", dir.path, test::library());
  CHECK(png.document["materials"]["png"]["normal_map"].is_string());
  // A missing normal map is an error at the statement.
  CHECK_THROWS_WITH_AS(import_pbrt_text(header + "Material \"diffuse\" \"string normalmap\" \"nowhere.png\"\n", "test.pbrt",
                                        dir.path, test::library()),
                       doctest::Contains("test.pbrt:4"), InputError);
}

}  // namespace normal_map_render_test
