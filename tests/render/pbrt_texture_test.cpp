// pbrt-v4 textures through the importer (docs/pbrt-import.md, "Texture"): float and spectrum texture classes become
// Rimu texture values where pbrt takes them, and a textured pbrt scene renders as its JSON twin.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/image/float_image_texture.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_image_files.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_texture_test {

const std::string kHeader = "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

PbrtImport import_text(const std::string& text, const std::filesystem::path& directory) {
  return import_pbrt_text(text, "test.pbrt", directory, test::library());
}

TEST_CASE("pbrt float textures: roughness and mix amounts from scale, mix, directionmix, checkerboard, imagemap") {
  test::ScratchFolder dir("pbrt_textures");
  const auto grey = test::write_ppm("pbrt_rough", 2, 1, {51, 0, 0, 255, 255, 255});
  std::filesystem::copy_file(grey, dir / "rough.ppm", std::filesystem::copy_options::overwrite_existing);
  const std::string textures =
      "Texture \"board\" \"float\" \"checkerboard\" \"float uscale\" 8 \"float vscale\" 4 \"float tex1\" 0.1 \"float tex2\" 0.4\n"
      "Texture \"scaled\" \"float\" \"scale\" \"texture tex\" \"board\" \"float scale\" 0.5\n"
      "Texture \"sideways\" \"float\" \"directionmix\" \"float tex1\" 0.2 \"texture tex2\" \"board\" \"vector3 dir\" [0 0 2]\n"
      "Texture \"map\" \"float\" \"imagemap\" \"string filename\" \"rough.ppm\" \"bool invert\" true \"float scale\" 0.5\n"
      "Texture \"blend\" \"float\" \"mix\" \"texture tex1\" \"scaled\" \"texture tex2\" \"map\" \"texture amount\" \"sideways\"\n";
  const PbrtImport imported = import_text(
      kHeader + textures +
          "MakeNamedMaterial \"metal\" \"string type\" \"conductor\" \"texture roughness\" \"blend\"\n"
          "MakeNamedMaterial \"raw\" \"string type\" \"conductor\" \"texture uroughness\" \"board\" \"float vroughness\" 0.09 \"bool remaproughness\" false\n"
          "MakeNamedMaterial \"frosted\" \"string type\" \"dielectric\" \"texture roughness\" \"map\"\n"
          "MakeNamedMaterial \"either\" \"string type\" \"mix\" \"string materials\" [\"metal\" \"frosted\"] \"texture amount\" \"board\"\n",
      dir.path);
  CHECK(imported.ignored.empty());
  const json& m = imported.document["materials"];
  const json board = {{"checkerboard", {0.1, 0.4}}, {"uv_scale", {8.0, 4.0}}, {"uv_offset", {0.0, 0.0}}};
  const json scaled = {{"product", {board, 0.5}}};
  // "dir" goes through the CTM of the Texture statement (here "Scale -1 1 1" then the camera: the world's z).
  const json sideways = {{"direction_mix", {0.2, board}}, {"direction", {0.0, 0.0, 2.0}}};
  // The first channel of a PPM: sRGB, as pbrt-v4 reads every 8-bit image but a PNG, inverted, scaled.
  const json map = m["frosted"]["roughness"]["power"][0];
  CHECK(map["texture"].get<std::string>().find("rough.ppm") != std::string::npos);
  CHECK(map["encoding"] == "srgb");
  CHECK(map["invert"] == true);
  CHECK(map["scale"] == 0.5);
  // Under remaproughness pbrt's α = roughness^½, Rimu's r = α^½: the texture is raised to ¼ per hit.
  CHECK(m["metal"]["roughness"] == json({{"power", {{{"mix", {scaled, map}}, {"amount", sideways}}, 0.25}}}));
  CHECK(m["raw"]["roughness_u"] == json({{"power", {board, 0.5}}}));
  CHECK(m["raw"]["roughness_v"].get<double>() == doctest::Approx(0.3));  // √0.09 without remapping
  CHECK(m["frosted"]["roughness"] == json({{"power", {map, 0.25}}}));
  CHECK(m["either"]["amount"] == board);
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", dir.path, test::library()));
}

TEST_CASE("pbrt spectrum textures and the conductor's reflectance") {
  test::ScratchFolder dir("pbrt_spectrum_textures");
  const PbrtImport imported = import_text(
      kHeader +
          "Texture \"tiles\" \"spectrum\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4 \"rgb tex1\" [0.8 0.1 0.1] \"float tex2\" 0.2\n"
          "Texture \"dim\" \"spectrum\" \"scale\" \"texture tex\" \"tiles\" \"float scale\" 0.5\n"
          "Texture \"faded\" \"spectrum\" \"mix\" \"texture tex1\" \"dim\" \"float tex2\" 0.9 \"float amount\" 0.25\n"
          "Texture \"up\" \"spectrum\" \"directionmix\" \"float tex1\" 0.7 \"texture tex2\" \"faded\"\n"
          "MakeNamedMaterial \"floor\" \"string type\" \"diffuse\" \"texture reflectance\" \"up\"\n"
          "MakeNamedMaterial \"gilt\" \"string type\" \"conductor\" \"rgb reflectance\" [0.9 0.7 0.3] \"float roughness\" 0.01\n"
          "MakeNamedMaterial \"leaf\" \"string type\" \"diffusetransmission\" \"texture transmittance\" \"tiles\"\n",
      dir.path);
  CHECK(imported.ignored.empty());
  const json& m = imported.document["materials"];
  const json tiles = {{"checkerboard", {test::pbrt_rgb_reflectance(0.8, 0.1, 0.1), 0.2}}, {"uv_scale", {4.0, 4.0}}, {"uv_offset", {0.0, 0.0}}};
  const json faded = {{"mix", {{{"product", {tiles, 0.5}}}, 0.9}}, {"amount", 0.25}};
  CHECK(m["floor"]["reflectance"] == json({{"direction_mix", {0.7, faded}}, {"direction", {0.0, 1.0, 0.0}}}));
  CHECK(m["gilt"]["reflectance"] == test::pbrt_rgb_reflectance(0.9, 0.7, 0.3));
  CHECK(!m["gilt"].contains("metal"));
  CHECK(m["gilt"]["roughness"].get<double>() == doctest::Approx(std::sqrt(std::sqrt(0.01))));
  CHECK(m["leaf"]["transmittance"] == tiles);
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", dir.path, test::library()));
}

TEST_CASE("pbrt imagemap encoding: a PNG takes \"encoding\" (sRGB by default), any other 8-bit file is sRGB, as pbrt-v4 reads it") {
  // pbrt-v4's texture defaults "encoding" to linear for a name not ending in .png, but its Image::Read hands that
  // encoding to the PNG reader only: TGA, JPEG, PPM, ... go through stb_image and are sRGB whatever is asked (the
  // Bitterli interiors' TGA textures render at pbrt's brightness only so).
  test::ScratchFolder dir("pbrt_spectrum_encoding");
  const auto ppm = test::write_ppm("pbrt_spectrum_encoding", 2, 1, {128, 128, 128, 255, 255, 255});
  std::filesystem::copy_file(ppm, dir / "paint.ppm", std::filesystem::copy_options::overwrite_existing);
  // The importer decides by the file name (pbrt does too); the bytes of these are never read.
  std::ofstream(dir / "paint.PNG") << "not read";
  std::ofstream(dir / "wood.tga") << "not read";
  const PbrtImport imported = import_text(
      kHeader +
          "Texture \"ppm\" \"spectrum\" \"imagemap\" \"string filename\" \"paint.ppm\"\n"
          "Texture \"ppmsrgb\" \"spectrum\" \"imagemap\" \"string filename\" \"paint.ppm\" \"string encoding\" \"sRGB\"\n"
          "Texture \"png\" \"spectrum\" \"imagemap\" \"string filename\" \"paint.PNG\"\n"
          "Texture \"pnglinear\" \"spectrum\" \"imagemap\" \"string filename\" \"paint.PNG\" \"string encoding\" \"linear\"\n"
          "Texture \"tga\" \"spectrum\" \"imagemap\" \"string filename\" \"wood.tga\"\n"
          "Texture \"tgalinear\" \"float\" \"imagemap\" \"string filename\" \"wood.tga\" \"string encoding\" \"linear\"\n"
          "MakeNamedMaterial \"a\" \"string type\" \"diffuse\" \"texture reflectance\" \"ppm\"\n"
          "MakeNamedMaterial \"b\" \"string type\" \"diffuse\" \"texture reflectance\" \"ppmsrgb\"\n"
          "MakeNamedMaterial \"c\" \"string type\" \"diffuse\" \"texture reflectance\" \"png\"\n"
          "MakeNamedMaterial \"d\" \"string type\" \"diffuse\" \"texture reflectance\" \"pnglinear\"\n"
          "MakeNamedMaterial \"e\" \"string type\" \"diffuse\" \"texture reflectance\" \"tga\"\n"
          "MakeNamedMaterial \"f\" \"string type\" \"conductor\" \"texture roughness\" \"tgalinear\"\n",
      dir.path);
  const json& m = imported.document["materials"];
  CHECK(m["a"]["reflectance"]["encoding"] == "srgb");  // was linear, by the texture's default alone
  CHECK(m["b"]["reflectance"]["encoding"] == "srgb");
  CHECK(m["c"]["reflectance"]["encoding"] == "srgb");
  CHECK(m["d"]["reflectance"]["encoding"] == "linear");
  CHECK(m["e"]["reflectance"]["encoding"] == "srgb");
  CHECK(m["f"]["roughness"]["power"][0]["encoding"] == "srgb");
  // Only the explicit "linear" on the TGA has no effect in either renderer: listed, once.
  REQUIRE(imported.ignored.size() == 1);
  CHECK(imported.ignored[0].what.find("linear") != std::string::npos);
  CHECK(imported.ignored[0].what.find(".tga") != std::string::npos);
}

TEST_CASE("pbrt textured ball renders as the same scene written in Rimu's JSON") {
  // cornell.pbrt's ball made of a red/white checkerboard, as pbrt text and as its hand-written JSON twin. Two
  // squares along pbrt's u = φ/2π about the ball's z-axis: the upper half (pbrt's y > 0, φ < π) one colour, the
  // lower the other; an offset of one square swaps them, which the comparison must see.
  const std::filesystem::path pbrt_file = test::test_data("pbrt/cornell.pbrt");
  std::stringstream text;
  text << std::ifstream(pbrt_file).rdbuf();
  std::string pbrt = text.str();
  const std::string green = "MakeNamedMaterial \"green\"";
  pbrt.insert(pbrt.find(green),
              "Texture \"tiles\" \"spectrum\" \"checkerboard\" \"float uscale\" 2 \"float vscale\" 1 "
              "\"rgb tex1\" [0.6 0.05 0.05] \"rgb tex2\" [0.7 0.7 0.7]\n"
              "MakeNamedMaterial \"tiled\" \"string type\" \"diffuse\" \"texture reflectance\" \"tiles\"\n");
  const std::string ball = "NamedMaterial \"white\"\n  Translate 0.45";
  REQUIRE(pbrt.find(ball) != std::string::npos);
  pbrt.replace(pbrt.find(ball), ball.size(), "NamedMaterial \"tiled\"\n  Translate 0.45");
  const PbrtImport imported = import_pbrt_text(pbrt, pbrt_file.string(), pbrt_file.parent_path(), test::library());
  CHECK(imported.ignored.empty());
  const auto from_pbrt = load_scene(imported.document, pbrt_file.string(), pbrt_file.parent_path(), test::library());

  std::ifstream in(test::test_data("pbrt/cornell_equivalent.json"));
  json hand_written = json::parse(in);
  const auto tiled = [](double u_offset) {
    return json{{"type", "diffuse"},
                {"reflectance", {{"checkerboard", {{{"rgb", {0.6, 0.05, 0.05}}}, {{"rgb", {0.7, 0.7, 0.7}}}}}, {"uv_scale", {2, 1}},
                                 {"uv_offset", {u_offset, 0}}}}};
  };
  hand_written["materials"]["tiled"] = tiled(0.0);
  for (json& shape : hand_written["shapes"])
    if (shape["type"] == "sphere") {
      shape["material"] = "tiled";
      // pbrt's object axes in Rimu's world: the ball is only translated and scaled, and the importer mirrors x.
      shape["uv_axes"] = {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    }
  const auto from_json = load_scene(hand_written, "cornell_equivalent.json", pbrt_file.parent_path(), test::library());
  const std::vector<double> a = test::luminance_values(*test::render_xyz(*from_pbrt, 128, 1).film);
  const std::vector<double> b = test::luminance_values(*test::render_xyz(*from_json, 128, 2).film);
  for (double deviation : test::block_deviations(a, b)) CHECK(deviation <= test::kSigmas);

  // The comparison can fail: the squares swapped (offset by one square along u).
  json swapped = hand_written;
  swapped["materials"]["tiled"] = tiled(1.0);
  const auto other = load_scene(swapped, "swapped.json", pbrt_file.parent_path(), test::library());
  const std::vector<double> c = test::luminance_values(*test::render_xyz(*other, 128, 3).film);
  double worst = 0.0;
  for (double deviation : test::block_deviations(a, c)) worst = std::max(worst, deviation);
  CHECK(worst > test::kSigmas);
}

TEST_CASE("float image texture: scale, then invert, as pbrt-v4's FloatImageTexture") {
  // Two texels, 51/255 = 0.2 and 1.0 (read linear); looked up at their centres.
  const auto path = test::write_ppm("float_image", 2, 1, {51, 0, 0, 255, 255, 255});
  const auto values = std::make_shared<const AlphaMask>(AlphaMask::read(path, 0, false, false));
  const ImageFloatTexture plain(values, 0.5f, false), inverted(values, 0.5f, true), over(values, 3.0f, true);
  const MaterialContext left = MaterialContext::at_uv({0.25f, 0.5f}), right = MaterialContext::at_uv({0.75f, 0.5f});
  CHECK(plain.evaluate(left) == doctest::Approx(0.1f));
  CHECK(plain.evaluate(right) == doctest::Approx(0.5f));
  CHECK(inverted.evaluate(left) == doctest::Approx(0.9f));   // 1 − 0.5·0.2, not 0.5·(1 − 0.2) = 0.4
  CHECK(inverted.evaluate(right) == doctest::Approx(0.5f));
  CHECK(over.evaluate(right) == 0.0f);                      // max(0, 1 − 3·1)
}

TEST_CASE("float image texture: values beyond [0, 1] kept as read (pbrt-v4 does not clamp), non-finite texels rejected") {
  // A float image (PFM, linear): 2.5 and -0.5 in the first channel, looked up at the texel centres.
  const auto path = test::write_pfm("float_image_unclamped", 2, 1, {2.5f, 0.0f, 0.0f, -0.5f, 0.0f, 0.0f});
  const auto values = std::make_shared<const AlphaMask>(AlphaMask::read(path, 0, false, false, false));
  const ImageFloatTexture plain(values, 2.0f, false), inverted(values, 1.0f, true);
  const MaterialContext left = MaterialContext::at_uv({0.25f, 0.5f}), right = MaterialContext::at_uv({0.75f, 0.5f});
  CHECK(plain.evaluate(left) == doctest::Approx(5.0f));   // was 2·1 when the texel was clamped at load
  CHECK(plain.evaluate(right) == doctest::Approx(-1.0f));  // was 0
  CHECK(inverted.evaluate(right) == doctest::Approx(1.5f));  // max(0, 1 − (−0.5))
  CHECK(inverted.evaluate(left) == 0.0f);                    // max(0, 1 − 2.5)
  // Coverage keeps its clamp.
  const AlphaMask coverage = AlphaMask::read(path, 0, false, false);
  CHECK(coverage.evaluate({0.25f, 0.5f}) == 1.0f);
  CHECK(coverage.evaluate({0.75f, 0.5f}) == 0.0f);
  const auto bad = test::write_pfm("float_image_nan", 2, 1, {0.5f, 0.0f, 0.0f, std::nanf(""), 0.0f, 0.0f});
  CHECK_THROWS_WITH_AS(AlphaMask::read(bad, 0, false, false, false), doctest::Contains("is not a finite number"), InputError);
}

TEST_CASE("pbrt default uv: a checkerboard on a trianglemesh without uv renders as its twin with pbrt's uvs written out") {
  // pbrt-v4 gives each triangle without uv (0,0), (1,0), (1,1) at its vertices (shapes.h, Triangle): on the quad
  // (0 1 2)(0 2 3) the checks of the two triangles do not line up. The twin writes those uvs out on unshared
  // corners; the barycentric convention (Rimu's default) is the control that the comparison sees the difference.
  for (const std::string& camera : {std::string("LookAt 0 0 0  0 0 1  0 1 0\n"), std::string("Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\n")}) {
    CAPTURE(camera);
    const PbrtImport imported = import_text(
        camera + "Camera \"perspective\" \"float fov\" 50\n"
                 "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 32\nWorldBegin\n"
                 "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
                 "Texture \"checks\" \"spectrum\" \"checkerboard\" \"float uscale\" 3 \"float vscale\" 3 "
                 "\"rgb tex1\" [0.9 0.9 0.9] \"rgb tex2\" [0.05 0.05 0.05]\n"
                 "Material \"diffuse\" \"texture reflectance\" \"checks\"\n"
                 "Shape \"trianglemesh\" \"point3 P\" [-2 -2 3  2 -2 3  2 2 3  -2 2 3] \"integer indices\" [0 1 2 0 2 3]\n",
        std::filesystem::temp_directory_path());
    CHECK(imported.ignored.empty());
    const json& shapes = imported.document["shapes"];
    REQUIRE(shapes.size() == 1);
    CHECK(shapes[0]["uv_default"] == "pbrt");
    json twin = imported.document;
    json& mesh = twin["shapes"][0];
    json corners = json::array(), indices = json::array(), uvs = json::array();
    const json pbrt_uv = {{0, 0}, {1, 0}, {1, 1}};
    for (size_t k = 0; k < mesh["indices"].size(); ++k) {
      corners.push_back(mesh["positions"][mesh["indices"][k].get<size_t>()]);
      uvs.push_back(pbrt_uv[k % 3]);
      indices.push_back(k);
    }
    mesh["positions"] = corners;
    mesh["indices"] = indices;
    mesh["uvs"] = uvs;
    mesh.erase("uv_default");
    json barycentric = imported.document;
    barycentric["shapes"][0]["uv_default"] = "barycentric";
    const auto dir = std::filesystem::temp_directory_path();
    const auto scene = load_scene(imported.document, "test.pbrt", dir, test::library());
    const auto twin_scene = load_scene(twin, "twin.json", dir, test::library());
    const auto control = load_scene(barycentric, "control.json", dir, test::library());
    CHECK(test::worst_deviation(test::render_block_deviations(*scene, *twin_scene)) <= test::kSigmas);
    CHECK(test::worst_deviation(test::render_block_deviations(*scene, *control)) > test::kSigmas);
  }
}

TEST_CASE("pbrt sphere: textures land where pbrt-v4 puts them (pole +z, u = φ/2π, v = 1 − θ/π, in object space)") {
  // Unmirrored header: pbrt's image-right (+x) is Rimu's left, so the importer mirrors the world x → −x.
  const PbrtImport imported = import_text(
      "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
      "Translate 0 0 5\nRotate 90 1 0 0\nScale 2 2 2\nShape \"sphere\" \"float radius\" 0.5\n",
      std::filesystem::temp_directory_path());
  CHECK(imported.ignored.empty());
  const json& sphere = imported.document["shapes"][0];
  REQUIRE(sphere["type"] == "sphere");
  // Object x, y, z through Rotate 90 about x ((x, y, z) → (x, −z, y)), then the mirror.
  const json want = {{-1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, -1.0, 0.0}};
  for (size_t k = 0; k < 3; ++k)
    for (size_t l = 0; l < 3; ++l) CHECK(sphere["uv_axes"][k][l].get<double>() == doctest::Approx(want[k][l].get<double>()).epsilon(1e-12));
  const auto scene = load_scene(imported.document, "test.pbrt", std::filesystem::temp_directory_path(), test::library());
  // pbrt's point of (u, v): object o = (sin θ cos φ, sin θ sin φ, cos θ), φ = 2πu, θ = π(1 − v); world =
  // (0, 0, 5) + (o.x, −o.z, o.y) by the CTM (radius 0.5 · scale 2 = 1), then x → −x.
  for (const auto& [u, v] : {std::pair{0.3f, 0.8f}, std::pair{0.05f, 0.4f}, std::pair{0.7f, 0.15f}, std::pair{0.95f, 0.6f}}) {
    CAPTURE(u);
    const double phi = 2 * M_PI * u, theta = M_PI * (1 - v);
    const Vec3 o{float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))};
    const Vec3 centre{0, 0, 5}, p = centre + Vec3{-o.x, -o.z, o.y};
    Ray ray;
    ray.origin = centre + (p - centre) * 3.0f;
    ray.direction = normalize(p - ray.origin);
    ray.t_min = 0.0f;
    ray.t_max = 1e30f;
    const auto hit = scene->geometry.intersect(ray);
    REQUIRE(hit);
    CHECK(hit->uv.x == doctest::Approx(u).epsilon(1e-4));
    CHECK(hit->uv.y == doctest::Approx(v).epsilon(1e-4));
  }
}

TEST_CASE("pbrt sphere as a mesh (squashed, emissive, with alpha) carries pbrt-v4's uv, an image alpha is kept") {
  test::ScratchFolder dir("pbrt_sphere_mesh_uv");
  const auto mask = test::write_ppm("pbrt_sphere_mask", 2, 1, {0, 0, 0, 255, 255, 255});
  std::filesystem::copy_file(mask, dir / "mask.ppm", std::filesystem::copy_options::overwrite_existing);
  const PbrtImport imported = import_text(kHeader +
                                              "Texture \"holes\" \"float\" \"imagemap\" \"string filename\" \"mask.ppm\"\n"
                                              "AttributeBegin\nScale 1 2 1\nShape \"sphere\" \"float radius\" 2\nAttributeEnd\n"
                                              "Shape \"sphere\" \"texture alpha\" \"holes\"\n",
                                          dir.path);
  CHECK(imported.ignored.empty());  // the image alpha was listed ("no texture coordinates") before
  const json& squashed = imported.document["shapes"][0];
  REQUIRE(squashed["type"] == "triangles");
  const auto positions = squashed["positions"].get<std::vector<std::array<double, 3>>>();
  const auto uvs = squashed["uvs"].get<std::vector<std::array<double, 2>>>();
  REQUIRE(uvs.size() == positions.size());
  for (size_t k = 0; k < positions.size(); ++k) {
    const auto [x, y, z] = positions[k];
    CAPTURE(k);
    // v = 1 − θ/π with cos θ = z/r (v = 1 at the +z pole); u = φ/2π away from the poles (the seam column: 0 or 1).
    CHECK(uvs[k][1] == doctest::Approx(1.0 - std::acos(std::clamp(z / 2.0, -1.0, 1.0)) / M_PI).epsilon(1e-9));
    if (std::hypot(x, y) > 1e-9) {
      double phi = std::atan2(y, x);
      if (phi < 0) phi += 2 * M_PI;
      const double u = uvs[k][0] >= 1.0 - 1e-12 && phi < 1e-9 ? 1.0 : phi / (2 * M_PI);
      CHECK(uvs[k][0] == doctest::Approx(u).epsilon(1e-9));
    }
  }
  const json& cut = imported.document["shapes"][1];
  CHECK(cut["type"] == "triangles");
  CHECK(cut["alpha"]["texture"].get<std::string>().find("mask.ppm") != std::string::npos);
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", dir.path, test::library()));
}

}  // namespace pbrt_texture_test
