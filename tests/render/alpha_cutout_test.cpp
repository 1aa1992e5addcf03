// Cut-outs ("alpha" on shapes): rays pass through the holes, camera rays (intersect) and shadow rays (occluded)
// alike, for EmbreeScene directly, for the JSON format and for pbrt-v4's "alpha" parameter; a render shows the
// background through the holes.
#include <OpenImageIO/imageio.h>
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "integration_support.h"
#include "render/image/alpha_mask.h"
#include "render/scene/embree_scene.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

// A 4×4 RGBA PNG: the left two columns are holes (R = A = 0), the right two solid (R = A = 255). Looked up
// bilinearly, u in [0.2, 0.3] reads only the left columns' texels (alpha 0), u in [0.7, 0.8] only the right's (1).
std::filesystem::path write_mask(const std::filesystem::path& path) {
  std::vector<unsigned char> pixels(4 * 4 * 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const unsigned char v = x < 2 ? 0 : 255;
      unsigned char* p = &pixels[size_t(4 * (y * 4 + x))];
      p[0] = v, p[1] = 128, p[2] = 128, p[3] = v;
    }
  auto out = OIIO::ImageOutput::create(path.string());
  REQUIRE(out);
  REQUIRE(out->open(path.string(), OIIO::ImageSpec(4, 4, 4, OIIO::TypeDesc::UINT8)));
  REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
  return path;
}

// The unit square in z = 0 with uv = (x, y), facing +z.
TriangleMesh unit_square(float z) {
  TriangleMesh m;
  m.positions = {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Ray down_from(float x, float y, float t_max = 1e30f) {
  Ray r;
  r.origin = {x, y, 1.0f};
  r.direction = {0, 0, -1};
  r.t_min = 0.0f;
  r.t_max = t_max;
  return r;
}

// For rays straight down at (x, y): where the first hit is (t = 1: the cut-out square at z = 0; t = 2: the
// backdrop at z = −1), and whether a shadow ray from z = 1 to z = −0.5 is blocked.
struct Probe {
  float t;
  bool shadowed;
};
Probe probe(const RayQueries& scene, float x, float y) {
  const auto hit = scene.intersect(down_from(x, y));
  REQUIRE(hit);
  return {hit->t, scene.occluded(down_from(x, y, 1.5f))};
}

// The front square's cut-out as seen through `scene`: holes where u < 0.5, solid where u > 0.5.
void check_holes(const RayQueries& scene) {
  for (float y : {0.1f, 0.5f, 0.9f}) {
    for (float x : {0.2f, 0.25f, 0.3f}) {
      CAPTURE(x);
      CAPTURE(y);
      const Probe p = probe(scene, x, y);
      CHECK(p.t == doctest::Approx(2.0));  // through the hole to the backdrop
      CHECK_FALSE(p.shadowed);
    }
    for (float x : {0.7f, 0.75f, 0.8f}) {
      CAPTURE(x);
      CAPTURE(y);
      const Probe p = probe(scene, x, y);
      CHECK(p.t == doctest::Approx(1.0));  // the solid part
      CHECK(p.shadowed);
    }
  }
}

json scene_document(const json& alpha) {
  json cutout = {{"type", "quad"}, {"material", "white"},
                 {"vertices", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}},
                 {"uvs", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}}};
  if (!alpha.is_null()) cutout["alpha"] = alpha;
  return {{"camera", {{"from", {0.5, 0.5, 3}}, {"to", {0.5, 0.5, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 18.925}}},
          {"film", {{"resolution", {16, 16}}, {"filter", {{"type", "box"}, {"radius", 0.5}}}}},
          {"integrator", {{"spp", 4}, {"max_depth", 2}}},
          {"materials", {{"white", {{"type", "diffuse"}, {"reflectance", 0}}}}},
          {"shapes",
           {cutout,
            {{"type", "quad"}, {"material", "white"}, {"vertices", {{-5, -5, -1}, {5, -5, -1}, {5, 5, -1}, {-5, 5, -1}}},
             {"emission", {{"rgb", {1, 1, 1}}}}}}}};
}

}  // namespace

TEST_CASE("alpha masks: constants, image channels, inversion and the stochastic rule") {
  test::ScratchFolder dir("alpha_mask");
  const auto path = write_mask(dir / "mask.png");
  const AlphaMask red = AlphaMask::read(path, 0, true, false);
  const AlphaMask alpha = AlphaMask::read(path, 3, false, false);
  const AlphaMask inverted = AlphaMask::read(path, 3, false, true);
  for (float v : {0.1f, 0.6f}) {
    CHECK(red.evaluate({0.25f, v}) == 0.0f);
    CHECK(red.evaluate({0.75f, v}) == 1.0f);
    CHECK(alpha.evaluate({0.25f, v}) == 0.0f);
    CHECK(alpha.evaluate({0.75f, v}) == 1.0f);
    CHECK(inverted.evaluate({0.25f, v}) == 1.0f);
    CHECK(alpha.evaluate({1.75f, v - 3.0f}) == 1.0f);  // coordinates repeat
  }
  // Green is 128 of 255 (read as stored, not multiplied by the alpha), sRGB-decoded: (128/255 + 0.055)/1.055)^2.4 = 0.2158605 (IEC 61966-2-1).
  CHECK(AlphaMask::read(path, 1, true, false).evaluate({0.5f, 0.5f}) == doctest::Approx(0.2158605).epsilon(1e-5));
  CHECK(AlphaMask::constant(1.7f).evaluate({0.3f, 0.3f}) == 1.0f);

  // A fractional alpha keeps that share of rays: 4,000 rays at alpha 0.3 keep 0.3 ± 5σ (σ = sqrt(0.21/4000)).
  int kept = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i)
    kept += alpha_keeps_hit(0.3f, {float(i) * 1e-3f, 0.5f, 1.0f}, normalize(Vec3{0.1f, float(i % 7) * 0.01f, -1.0f}));
  CHECK(std::abs(double(kept) / n - 0.3) < 5 * std::sqrt(0.21 / n));
  // The same ray always gets the same answer, and alpha 0 and 1 are certain.
  CHECK(alpha_keeps_hit(0.5f, {1, 2, 3}, {0, 0, -1}) == alpha_keeps_hit(0.5f, {1, 2, 3}, {0, 0, -1}));
  CHECK_FALSE(alpha_keeps_hit(0.0f, {1, 2, 3}, {0, 0, -1}));
  CHECK(alpha_keeps_hit(1.0f, {1, 2, 3}, {0, 0, -1}));
}

TEST_CASE("alpha cut-outs in Embree: camera and shadow rays pass through the holes, also in instances") {
  test::ScratchFolder dir("alpha_embree");
  const auto mask = std::make_shared<const AlphaMask>(AlphaMask::read(write_mask(dir / "mask.png"), 3, false, false));
  SUBCASE("a mesh") {
    EmbreeScene scene;
    scene.add_mesh(unit_square(0.0f), 0, -1, mask);
    TriangleMesh back = unit_square(-1.0f);
    for (Vec3& p : back.positions) p = {p.x * 4 - 2, p.y * 4 - 2, p.z};
    scene.add_mesh(back, 0, -1);
    scene.commit();
    check_holes(scene);
  }
  SUBCASE("an instance of a prototype with a cut-out") {
    EmbreeScene scene;
    std::vector<std::pair<TriangleMesh, int>> meshes;
    meshes.emplace_back(unit_square(0.0f), 0);
    const int prototype = scene.add_prototype(std::move(meshes), {mask});
    scene.add_instance(prototype, Transform::translate({0, 0, 0.5f}));
    TriangleMesh back = unit_square(-1.0f);
    for (Vec3& p : back.positions) p = {p.x * 4 - 2, p.y * 4 - 2, p.z};
    scene.add_mesh(back, 0, -1);
    scene.commit();
    const Probe hole = probe(scene, 0.25f, 0.5f), solid = probe(scene, 0.75f, 0.5f);
    CHECK(hole.t == doctest::Approx(2.0));
    CHECK_FALSE(hole.shadowed);
    CHECK(solid.t == doctest::Approx(0.5));
    CHECK(solid.shadowed);
  }
}

TEST_CASE("JSON \"alpha\": an image channel cuts holes the camera sees the emitter through") {
  test::ScratchFolder dir("alpha_json");
  write_mask(dir / "mask.png");
  const json document = scene_document({{"texture", "mask.png"}, {"channel", "a"}});
  const auto scene = load_scene(document, "cutout.json", dir.path, test::library());
  check_holes(scene->geometry);

  // The render: a black square in front of an emitter, filling the image (2·atan(0.5/3) = 18.925°). Through the
  // holes the emitter shows; the solid part is black. Rimu's camera has image-right along +x here, so columns 2-5
  // (0.125 ≤ x ≤ 0.375: only hole texels in the bilinear lookup) see holes, columns 10-13 (0.625 ≤ x ≤ 0.875)
  // only solid ones; nearer the edges the repeating lookup blends in the texels of the other side.
  const std::vector<double> y = test::luminance_values(*test::render_xyz(*scene, 4, 1).film);
  REQUIRE(y.size() == 256);
  double left = 0, right = 0;
  for (int row = 2; row < 14; ++row)
    for (int col = 2; col < 6; ++col) {
      left += y[size_t(row * 16 + col)];
      right += y[size_t(row * 16 + 15 - col)];
    }
  CHECK(left > 0.0);
  CHECK(right == 0.0);
  // Without the alpha the whole square is black.
  const auto solid = load_scene(scene_document(nullptr), "solid.json", dir.path, test::library());
  const std::vector<double> ys = test::luminance_values(*test::render_xyz(*solid, 4, 1).film);
  double solid_left = 0;
  for (int row = 2; row < 14; ++row)
    for (int col = 2; col < 6; ++col) solid_left += ys[size_t(row * 16 + col)];
  CHECK(solid_left == 0.0);

  // Errors name the key.
  auto bad = document;
  bad["shapes"][0]["alpha"]["channel"] = "q";
  CHECK_THROWS_WITH_AS(load_scene(bad, "bad.json", dir.path, test::library()), doctest::Contains("/shapes/0/alpha/channel"), InputError);
  bad = scene_document(json({{"texture", "missing.png"}}));
  CHECK_THROWS_WITH_AS(load_scene(bad, "bad.json", dir.path, test::library()), doctest::Contains("/shapes/0/alpha/texture"), InputError);
  bad = scene_document(1.5);
  CHECK_THROWS_AS(load_scene(bad, "bad.json", dir.path, test::library()), InputError);
  bad = document;
  bad["shapes"][1]["alpha"] = 0.5;
  CHECK_THROWS_WITH_AS(load_scene(bad, "bad.json", dir.path, test::library()), doctest::Contains("emissive"), InputError);
}

TEST_CASE("pbrt \"alpha\": a float imagemap on a bilinear patch, a constant, and what is left solid") {
  test::ScratchFolder dir("alpha_pbrt");
  write_mask(dir / "mask.png");
  const std::string header =
      "Scale -1 1 1\nLookAt 0.5 0.5 3  0.5 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" 10\nWorldBegin\n"
      "Texture \"holes\" \"float\" \"imagemap\" \"string filename\" \"mask.png\"\n";
  const std::string patch = "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0]";
  const std::string backdrop =
      "\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
      "Shape \"trianglemesh\" \"point3 P\" [-5 -5 -1  5 -5 -1  5 5 -1  -5 5 -1] \"integer indices\" [0 1 2 0 2 3]\n"
      "AttributeEnd\n";
  const PbrtImport imported =
      import_pbrt_text(header + patch + " \"texture alpha\" \"holes\"" + backdrop, "cutout.pbrt", dir.path, test::library());
  const json& alpha = imported.document["shapes"][0]["alpha"];
  CHECK(alpha["channel"] == "r");  // a float imagemap reads the first channel, as pbrt-v4 does
  CHECK(alpha["encoding"] == "srgb");  // pbrt's default for PNG
  const auto scene = load_scene(imported.document, "cutout.pbrt", dir.path, test::library());
  check_holes(scene->geometry);
  CHECK(imported.ignored.empty());

  // A constant alpha of 0 leaves nothing to hit; 1 is solid (no key at all).
  const PbrtImport clear = import_pbrt_text(header + patch + " \"float alpha\" 0" + backdrop, "c.pbrt", dir.path, test::library());
  CHECK(clear.document["shapes"][0]["alpha"] == 0.0);
  const auto clear_scene = load_scene(clear.document, "c.pbrt", dir.path, test::library());
  CHECK(probe(clear_scene->geometry, 0.75f, 0.5f).t == doctest::Approx(2.0));
  const PbrtImport solid = import_pbrt_text(header + patch + " \"float alpha\" 1" + backdrop, "s.pbrt", dir.path, test::library());
  CHECK_FALSE(solid.document["shapes"][0].contains("alpha"));

  // A disk carries pbrt's uv, so its image alpha is kept.
  const PbrtImport disk = import_pbrt_text(header + "Shape \"disk\" \"texture alpha\" \"holes\"" + backdrop, "d.pbrt", dir.path, test::library());
  CHECK(disk.document["shapes"][0]["alpha"].contains("texture"));
  CHECK(disk.ignored.empty());
  // An image alpha on a shape without texture coordinates in Rimu (bilinear patches sharing vertices, whose default
  // uv is per patch) is listed and the shape left solid.
  const PbrtImport patches = import_pbrt_text(
      header + "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0  2 0 0  2 1 0] \"integer indices\" [0 1 2 3  1 4 3 5] "
               "\"texture alpha\" \"holes\"" + backdrop,
      "b.pbrt", dir.path, test::library());
  CHECK_FALSE(patches.document["shapes"][0].contains("alpha"));
  REQUIRE_FALSE(patches.ignored.empty());
  CHECK(describe_ignored(patches.ignored).find("alpha image texture on a shape without texture coordinates") != std::string::npos);
  // A spectrum texture is refused with the line.
  CHECK_THROWS_WITH_AS(import_pbrt_text(header + "Texture \"c\" \"spectrum\" \"constant\"\n" + patch + " \"texture alpha\" \"c\"",
                                        "e.pbrt", dir.path, test::library()),
                       doctest::Contains("e.pbrt:7"), InputError);
}
