// pbrt-v4 geometry details (docs/pbrt-import.md, Shapes): .ply.gz meshes, bilinear patches, partial spheres listed,
// degenerate triangles removed and counted.
#include <doctest/doctest.h>

#include <string>

#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

const std::string kCamera = "Scale -1 1 1\nLookAt 0.5 0.5 3  0.5 0.5 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

PbrtImport import_text(const std::string& text) {
  return import_pbrt_text(kCamera + text, "geometry.pbrt", test::test_data("pbrt"), test::library());
}

std::optional<float> hit_distance_down(const Scene& scene, float x, float y) {
  Ray r;
  r.origin = {x, y, 1.0f};
  r.direction = {0, 0, -1};
  r.t_min = 0.0f;
  r.t_max = 1e30f;
  const auto hit = scene.geometry.intersect(r);
  return hit ? std::optional<float>(hit->t) : std::nullopt;
}

}  // namespace

TEST_CASE("pbrt plymesh reads .ply.gz: the same quad as the .ply") {
  for (const char* file : {"quad.ply", "quad.ply.gz"}) {
    CAPTURE(file);
    const PbrtImport imported = import_text(std::string("Shape \"plymesh\" \"string filename\" \"") + file + "\"");
    CHECK(imported.ignored.empty());
    const auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
    // quad.ply is the unit square in z = 0.
    const auto inside = hit_distance_down(*scene, 0.5f, 0.5f);
    REQUIRE(inside);
    CHECK(*inside == doctest::Approx(1.0));
    CHECK_FALSE(hit_distance_down(*scene, 1.5f, 0.5f));
  }
}

TEST_CASE("pbrt bilinearmesh: two triangles per patch and pbrt's default uv for a single patch") {
  const json d = import_text("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0]").document;
  const json& shape = d["shapes"][0];
  CHECK(shape["indices"] == json({0, 1, 3, 0, 3, 2}));
  CHECK(shape["uvs"] == json({{0, 0}, {1, 0}, {0, 1}, {1, 1}}));
  // Two patches sharing an edge keep their indices; no default uv (vertices are shared between patches).
  const json two = import_text("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0  2 0 0  2 1 0] "
                               "\"integer indices\" [0 1 2 3  1 4 3 5]")
                       .document["shapes"][0];
  CHECK(two["indices"] == json({0, 1, 3, 0, 3, 2, 1, 4, 5, 1, 5, 3}));
  CHECK_FALSE(two.contains("uvs"));
}

TEST_CASE("pbrt partial spheres are listed; degenerate triangles are removed and counted") {
  for (const char* parameter : {"\"float zmin\" -0.5", "\"float zmax\" 0.5", "\"float phimax\" 180"}) {
    CAPTURE(parameter);
    const PbrtImport imported = import_text(std::string("Shape \"sphere\" ") + parameter);
    CHECK(describe_ignored(imported.ignored).find("partial sphere") != std::string::npos);
  }
  CHECK(import_text("Shape \"sphere\" \"float zmin\" -1 \"float zmax\" 1 \"float phimax\" 360").ignored.empty());

  // Triangle 1 repeats a vertex, triangle 2 has three collinear ones: both have zero area.
  const PbrtImport imported = import_text(
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  1 1 0  2 2 0] \"integer indices\" [0 1 2  0 1 1  0 2 3]");
  const auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
  CHECK(scene->degenerate_triangles_removed == 2);
  REQUIRE(scene->warnings.size() == 1);  // printed by rimu before rendering
  CHECK(scene->warnings[0].find("2 degenerate triangles") == 0);
  CHECK(hit_distance_down(*scene, 0.8f, 0.2f));
}
