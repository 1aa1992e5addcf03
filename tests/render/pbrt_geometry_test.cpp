// pbrt-v4 geometry details (docs/pbrt-import.md, Shapes): .ply.gz meshes, bilinear patches, partial spheres,
// cylinders and disks as meshes (emissive too), whole emissive spheres as analytic lights, degenerate triangles
// removed and counted.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "test_support.h"
#include "transport/lights/area_light.h"
#include "transport/lights/bvh_light_sampler.h"
#include "transport/lights/sphere_light.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_geometry_test {

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

TEST_CASE("pbrt partial spheres, cylinders and disks become meshes with pbrt's normals and uv, empty ones are listed") {
  // A partial sphere: every vertex on the sphere inside zmin/zmax and φ ≤ φmax, nothing listed.
  const PbrtImport sphere = import_text("Shape \"sphere\" \"float radius\" 2 \"float zmin\" -0.5 \"float zmax\" 1 \"float phimax\" 90");
  CHECK(sphere.ignored.empty());
  const json& s = sphere.document["shapes"][0];
  REQUIRE(s["type"] == "triangles");
  for (size_t i = 0; i < s["positions"].size(); ++i) {
    const auto p = s["positions"][i].get<std::array<double, 3>>();
    CHECK(std::hypot(p[0], p[1], p[2]) == doctest::Approx(2.0).epsilon(1e-6));
    CHECK(p[2] >= -0.5 - 1e-6);
    CHECK(p[2] <= 1 + 1e-6);
    CHECK(p[0] >= -1e-6);
    CHECK(p[1] >= -1e-6);
    CHECK(s["uvs"][i][0].get<double>() <= 1.0);
  }
  // A cylinder: outward normals, pbrt's uv; ReverseOrientation turns the normals (and the winding) inward.
  for (const bool reversed : {false, true}) {
    CAPTURE(reversed);
    const PbrtImport imported = import_text(std::string(reversed ? "ReverseOrientation\n" : "") +
                                            "Shape \"cylinder\" \"float radius\" 0.5 \"float zmin\" 2 \"float zmax\" 0");
    CHECK(imported.ignored.empty());
    const json& c = imported.document["shapes"][0];
    REQUIRE(c["type"] == "triangles");
    for (size_t i = 0; i < c["positions"].size(); ++i) {
      const auto p = c["positions"][i].get<std::array<double, 3>>();
      const auto n = c["normals"][i].get<std::array<double, 3>>();
      CHECK(n[0] * p[0] + n[1] * p[1] == doctest::Approx(reversed ? -0.5 : 0.5).epsilon(1e-5));
      CHECK(c["uvs"][i][1].get<double>() == doctest::Approx(p[2] / 2));  // zmin/zmax ordered as pbrt does
    }
  }
  // A disk now carries pbrt's uv (v = 1 at the inner radius).
  const json disk = import_text("Shape \"disk\" \"float innerradius\" 0.5").document["shapes"][0];
  CHECK(disk["uvs"][1] == json({0.0, 1.0}));
  // Shapes of zero area are listed, as pbrt renders nothing there.
  for (const char* shape : {"\"sphere\" \"float zmin\" 0.5 \"float zmax\" 0.5", "\"cylinder\" \"float phimax\" 0",
                            "\"disk\" \"float phimax\" 0"}) {
    CAPTURE(shape);
    const PbrtImport imported = import_text(std::string("Shape ") + shape);
    CHECK(imported.document["shapes"].empty());
    CHECK(describe_ignored(imported.ignored).find("of zero area") != std::string::npos);
  }
}

TEST_CASE("pbrt emissive cylinder and disk: area lights with pbrt's area, emitting outward") {
  const PbrtImport imported = import_text("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
                                          "Shape \"cylinder\" \"float radius\" 0.1 \"float zmin\" 0 \"float zmax\" 1\n"
                                          "Shape \"disk\" \"float radius\" 0.2\nAttributeEnd\n");
  CHECK(imported.ignored.empty());
  const auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
  REQUIRE(scene->lights.size() == 2);
  const double cylinder = 2 * std::numbers::pi * 0.1, disk = std::numbers::pi * 0.04;
  const auto& tube = dynamic_cast<const AreaLight&>(*scene->lights[0]);
  const auto& lid = dynamic_cast<const AreaLight&>(*scene->lights[1]);
  CHECK(tube.area_m2() == doctest::Approx(cylinder).epsilon(1e-3));
  CHECK(lid.area_m2() == doctest::Approx(disk).epsilon(1e-3));
  // One-sided, outward: the tube lights a point beside it and not one inside it on its axis.
  const SampledWavelengths lambda(Float4(550.0f), Float4(1.0f));
  const auto lit_samples = [&](const LightReference& ref) {
    int lit = 0;
    for (int i = 0; i < 64; ++i) {
      const auto sample = tube.sample_li(ref, lambda, {(i % 8 + 0.5f) / 8, (i / 8 + 0.5f) / 8});
      lit += sample && sample->radiance[0] > 0.0f;
    }
    return lit;
  };
  CHECK(lit_samples({{1, 0, 0.5}, {-1, 0, 0}}) > 0);
  CHECK(lit_samples({{0, 0, 0.5}, {1, 0, 0}}) == 0);
}

TEST_CASE("pbrt quadrics under a mirroring transform emit on the side pbrt's normals face") {
  // pbrt-v4 flips a shape's normal when its transform swaps handedness (reverseOrientation ^
  // transformSwapsHandedness), which leaves every quadric's normal equal to its object-space normal transformed as a
  // normal: a sphere and a cylinder still face away from their centre and axis, and a disk mirrored through its
  // plane (Scale 1 1 -1) faces −z. ReverseOrientation on top turns it back. An area light emits on that side only.
  const SampledWavelengths lambda(Float4(550.0f), Float4(1.0f));
  // Of 64 stratified light samples seen from `position` (a point in space: no surface to cull behind), how many
  // carry light.
  const auto lit_samples = [&](const Light& light, Vec3 position) {
    int lit = 0;
    for (int i = 0; i < 64; ++i) {
      const auto sample = light.sample_li({position, {0, 0, 0}}, lambda, {(i % 8 + 0.5f) / 8, (i / 8 + 0.5f) / 8});
      lit += sample && sample->radiance[0] > 0.0f;
    }
    return lit;
  };
  const auto only_light = [&](const std::string& transform, const std::string& shape) {
    const PbrtImport imported = import_text("AttributeBegin\n" + transform + "\nAreaLightSource \"diffuse\" \"rgb L\" "
                                            "[1 1 1]\nShape " + shape + "\nAttributeEnd\n");
    CHECK(imported.ignored.empty());
    auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
    REQUIRE(scene->lights.size() == 1);
    return scene;
  };
  struct MirroredDisk {
    const char* transform;
    float world_z;  // of the disk's plane (object height 0.25)
    bool faces_down;
  };
  for (const MirroredDisk& c : {MirroredDisk{"Scale 1 1 -1", -0.25f, true}, {"Scale 1 1 -1\nReverseOrientation", -0.25f, false},
                                {"Scale -1 1 1", 0.25f, false}, {"Scale -1 -1 -1", -0.25f, true}}) {
    CAPTURE(c.transform);
    const auto scene = only_light(c.transform, "\"disk\" \"float radius\" 0.5 \"float height\" 0.25");
    const int below = lit_samples(*scene->lights[0], {0, 0, c.world_z - 1});
    const int above = lit_samples(*scene->lights[0], {0, 0, c.world_z + 1});
    CHECK((c.faces_down ? below : above) == 64);
    CHECK((c.faces_down ? above : below) == 0);
  }
  for (const char* transform : {"Scale -1 1 1", "Scale 1 1 -1", "Scale -2 2 2"}) {
    CAPTURE(transform);
    // A cylinder along z lights a point beside it and not one on its axis inside it.
    const auto tube = only_light(transform, "\"cylinder\" \"float radius\" 0.1 \"float zmin\" -0.5 \"float zmax\" 0.5");
    CHECK(lit_samples(*tube->lights[0], {1, 0, 0}) > 0);
    CHECK(lit_samples(*tube->lights[0], {0, 0, 0}) == 0);
    // A sphere, full and partial, lights a point outside and none at its centre.
    for (const char* sphere : {"\"sphere\" \"float radius\" 0.3", "\"sphere\" \"float radius\" 0.3 \"float zmax\" 0.2"}) {
      CAPTURE(sphere);
      const auto ball = only_light(transform, sphere);
      CHECK(lit_samples(*ball->lights[0], {2, 0, 0}) > 0);
      CHECK(lit_samples(*ball->lights[0], {0, 0, 0}) == 0);
    }
  }
}

TEST_CASE("pbrt emissive spheres: a whole one under a similarity is one analytic light, the others stay meshes") {
  const auto import_light = [](const std::string& transform, const std::string& light, const std::string& shape) {
    const PbrtImport imported = import_text("AttributeBegin\n" + transform + "\nAreaLightSource \"diffuse\" " + light +
                                            "\nShape \"sphere\" " + shape + "\nAttributeEnd\n");
    CHECK(imported.ignored.empty());
    return imported;
  };
  SUBCASE("whole, translated, rotated and uniformly scaled: one SphereLight, one light tree leaf") {
    const PbrtImport imported = import_light("Translate 1 2 3\nRotate 30 1 1 0\nScale 2 2 2", "\"rgb L\" [1 1 1]",
                                             "\"float radius\" 0.25");
    const json& shape = imported.document["shapes"][0];
    CHECK(shape["type"] == "sphere");
    CHECK(shape["radius"].get<double>() == doctest::Approx(0.5));
    CHECK(shape.contains("emission"));
    const auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
    REQUIRE(scene->lights.size() == 1);
    const auto* sphere = dynamic_cast<const SphereLight*>(scene->lights[0].get());
    REQUIRE(sphere);
    CHECK(sphere->radius_m() == doctest::Approx(0.5));
    CHECK(sphere->centre_m().x == doctest::Approx(1.0));
    CHECK(sphere->centre_m().y == doctest::Approx(2.0));
    CHECK(sphere->centre_m().z == doctest::Approx(3.0));
    CHECK_FALSE(sphere->two_sided());
    CHECK(sphere->part_count() == 1);
    const auto* tree = dynamic_cast<const BvhLightSampler*>(scene->light_sampler.get());
    REQUIRE(tree);
    CHECK(tree->leaf_count() == 1);
    // A ray from above meets the sphere and finds its light.
    Ray r;
    r.origin = {1.0f, 2.0f, 5.0f};
    r.direction = {0, 0, -1};
    r.t_min = 0.0f;
    r.t_max = 1e30f;
    const auto hit = scene->geometry.intersect(r);
    REQUIRE(hit);
    CHECK(hit->light == 0);
    CHECK(hit->t == doctest::Approx(1.5));
  }
  SUBCASE("twosided carries over") {
    const PbrtImport imported = import_light("", "\"rgb L\" [1 1 1] \"bool twosided\" true", "\"float radius\" 0.25");
    const auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
    const auto* sphere = dynamic_cast<const SphereLight*>(scene->lights.at(0).get());
    REQUIRE(sphere);
    CHECK(sphere->two_sided());
  }
  SUBCASE("\"power\": pbrt-v4 spreads it over the object-space area, so Scale 2 emits 4 times it") {
    // (The amount is in the importer's units, pbrt's "nits" times nits_per_unit_y: compared between the two.)
    std::vector<double> lumens;
    for (const char* scale : {"1 1 1", "2 2 2"}) {
      CAPTURE(scale);
      const PbrtImport imported = import_light(std::string("Scale ") + scale, "\"rgb L\" [1 1 1] \"float power\" 100",
                                               "\"float radius\" 0.25");
      const json& emission = imported.document["shapes"][0]["emission"];
      CAPTURE(emission.dump());
      REQUIRE(emission.contains("luminous_power_lm"));
      lumens.push_back(emission["luminous_power_lm"].get<double>());
    }
    CHECK(lumens[1] == doctest::Approx(4.0 * lumens[0]).epsilon(1e-12));
  }
  SUBCASE("partial, reversed and squashed spheres are tessellated area lights") {
    for (const auto& [transform, shape] : {std::pair<std::string, std::string>{"", "\"float radius\" 0.25 \"float zmax\" 0.1"},
                                           {"ReverseOrientation", "\"float radius\" 0.25"},
                                           {"Scale 1 1 2", "\"float radius\" 0.25"}}) {
      CAPTURE(transform);
      CAPTURE(shape);
      const PbrtImport imported = import_light(transform, "\"rgb L\" [1 1 1]", shape);
      CHECK(imported.document["shapes"][0]["type"] == "triangles");
      const auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
      REQUIRE(scene->lights.size() == 1);
      const auto* mesh = dynamic_cast<const AreaLight*>(scene->lights[0].get());
      REQUIRE(mesh);
      const auto* tree = dynamic_cast<const BvhLightSampler*>(scene->light_sampler.get());
      REQUIRE(tree);
      CHECK(tree->leaf_count() == mesh->triangle_count() - mesh->degenerate_triangle_count());
      CHECK(tree->leaf_count() > 1000);
    }
  }
}

TEST_CASE("pbrt degenerate triangles are removed and counted") {
  // Triangle 1 repeats a vertex, triangle 2 has three collinear ones: both have zero area.
  const PbrtImport imported = import_text(
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  1 1 0  2 2 0] \"integer indices\" [0 1 2  0 1 1  0 2 3]");
  const auto scene = load_scene(imported.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
  CHECK(scene->degenerate_triangles_removed == 2);
  REQUIRE(scene->warnings.size() == 1);  // printed by rimu before rendering
  CHECK(scene->warnings[0].find("2 degenerate triangles") == 0);
  CHECK(hit_distance_down(*scene, 0.8f, 0.2f));
}

TEST_CASE("pbrt meshes whose shading normals lie in their triangles' plane are listed and warned about") {
  // buddha-fractal's floor (docs/benchmarks.md, "Real-scene corpus"): a quad in z = 0 with every N along +y.
  const std::string floor = "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  1 1 0  0 1 0] \"integer indices\" [0 1 2  0 2 3]";
  const PbrtImport in_plane = import_text(floor + " \"normal N\" [0 1 0  0 1 0  0 1 0  0 1 0]");
  const std::string listed = describe_ignored(in_plane.ignored);
  CAPTURE(listed);
  REQUIRE(in_plane.ignored.size() == 1);
  CHECK(listed.find("Shape \"trianglemesh\" with shading normals \"N\" in (or across) the plane") != std::string::npos);
  CHECK(listed.find("pbrt-v4 follows them") != std::string::npos);
  const auto scene = load_scene(in_plane.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
  CHECK(scene->meshes_with_normals_near_plane == 1);
  REQUIRE(scene->warnings.size() == 1);  // the loader says it for JSON meshes too
  CHECK(scene->warnings[0].find("1 meshes have shading normals in (or across) the plane") == 0);

  // Normals across the plane (one vertex's behind it) are listed too; normals tilted 60° off the face are not.
  CHECK(import_text(floor + " \"normal N\" [0 0 1  0 0 1  0 0.5 -1  0 0 1]").ignored.size() == 1);
  const PbrtImport tilted = import_text(floor + " \"normal N\" [0 0.866 0.5  0 0.866 0.5  0 0.866 0.5  0 0.866 0.5]");
  CHECK_MESSAGE(tilted.ignored.empty(), describe_ignored(tilted.ignored));
  CHECK(load_scene(tilted.document, "geometry.pbrt", test::test_data("pbrt"), test::library())->warnings.empty());
}

TEST_CASE("a mesh with shading normals in the plane of under 1 % of its triangles is not listed (a crease)") {
  // 200 triangles of a strip in z = 0 with normals +z, but one vertex's normal along +x, which only one triangle
  // uses (0.5 %).
  std::string p = "\"point3 P\" [", n = "\"normal N\" [", idx = "\"integer indices\" [";
  for (int i = 0; i <= 100; ++i) {
    p += std::to_string(i) + " 0 0  " + std::to_string(i) + " 1 0  ";
    n += i == 100 ? "1 0 0  0 0 1  " : "0 0 1  0 0 1  ";
  }
  for (int i = 0; i < 100; ++i) {
    const int a = 2 * i, b = 2 * i + 2, c = 2 * i + 3, d = 2 * i + 1;
    idx += std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "  " + std::to_string(a) + " " +
           std::to_string(c) + " " + std::to_string(d) + "  ";
  }
  const PbrtImport strip = import_text("Shape \"trianglemesh\" " + p + "] " + n + "] " + idx + "]");
  CHECK_MESSAGE(strip.ignored.empty(), describe_ignored(strip.ignored));
  // The same normal on half of a 2-triangle mesh is listed.
  const PbrtImport half = import_text(
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  1 1 0  0 1 0] \"integer indices\" [0 1 2  0 2 3] "
      "\"normal N\" [0 0 1  1 0 0  0 0 1  0 0 1]");
  CHECK(half.ignored.size() == 1);
}

TEST_CASE("normals in the plane are counted by area: a scanned mesh's slivers are not, one large triangle is") {
  // A 10 × 10 quad in z = 0 (normals +z) and 20 slivers of 0.01 × 0.01 beside it whose normals lie along +x, as a
  // scanned mesh has them (buddha-fractal's statue: 3.6 % of its triangles, 0.42 % of its area): 91 % of the
  // triangles, 0.001 % of the area.
  std::string p = "\"point3 P\" [0 0 0  10 0 0  10 10 0  0 10 0", n = "\"normal N\" [0 0 1  0 0 1  0 0 1  0 0 1",
              idx = "\"integer indices\" [0 1 2  0 2 3";
  for (int i = 0; i < 20; ++i) {
    const std::string x = std::to_string(11 + i);
    p += "  " + x + " 0 0  " + x + ".01 0 0  " + x + " 0.01 0";
    n += "  1 0 0  1 0 0  1 0 0";
    idx += "  " + std::to_string(4 + 3 * i) + " " + std::to_string(5 + 3 * i) + " " + std::to_string(6 + 3 * i);
  }
  const std::string slivers = p + "] " + n + "] " + idx + "]";
  const PbrtImport scanned = import_text("Shape \"trianglemesh\" " + slivers);
  CHECK_MESSAGE(scanned.ignored.empty(), describe_ignored(scanned.ignored));
  CHECK(load_scene(scanned.document, "geometry.pbrt", test::test_data("pbrt"), test::library())->warnings.empty());
  // The same mesh with the quad's normals in its plane: 9 % of the triangles, 99.999 % of the area.
  std::string turned = slivers;
  const std::string up = "0 0 1  0 0 1  0 0 1  0 0 1";
  turned.replace(turned.find(up), up.size(), "0 1 0  0 1 0  0 1 0  0 1 0");
  const PbrtImport floor = import_text("Shape \"trianglemesh\" " + turned);
  CHECK(floor.ignored.size() == 1);
  const auto scene = load_scene(floor.document, "geometry.pbrt", test::test_data("pbrt"), test::library());
  CHECK(scene->meshes_with_normals_near_plane == 1);
}

TEST_CASE("pbrt plymesh: a vertex normal that is NaN (as in pbrt-v4) or zero shades its triangles flat, the others keep theirs") {
  // Bitterli's lamp exports NaN normals at some vertices; pbrt-v4 interpolates them into a NaN normal, which falls
  // back to the geometric one (Triangle::InteractionFromIntersection), and Rimu refused the file. (A zero normal,
  // which pbrt-v4 leaves out of the blend of the other two, is flat in Rimu too: one "no normal" mark.) Three separate
  // triangles in z = 0, counter-clockwise from +z; normals tilted towards +x except vertex 0 (NaN) and 5 (zero).
  test::ScratchFolder dir("pbrt_nan_normals");
  const std::string tilted = " 0.6 0 0.8\n";
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 9\nproperty float x\nproperty float y\nproperty float z\n"
                          "property float nx\nproperty float ny\nproperty float nz\nelement face 3\n"
                          "property list uchar int vertex_indices\nend_header\n"
                          "0 0 0 nan nan nan\n1 0 0" + tilted + "0 1 0" + tilted +
                          "2 0 0" + tilted + "3 0 0" + tilted + "2 1 0 0 0 0\n" +
                          "4 0 0" + tilted + "5 0 0" + tilted + "4 1 0" + tilted +
                          "3 0 1 2\n3 3 4 5\n3 6 7 8\n";
  dir.write("odd_normals.ply", ply);
  const PbrtImport imported = import_pbrt_text(kCamera + "Shape \"plymesh\" \"string filename\" \"odd_normals.ply\"",
                                               "geometry.pbrt", dir.path, test::library());
  const auto scene = load_scene(imported.document, "geometry.pbrt", dir.path, test::library());
  REQUIRE(scene->warnings.size() == 1);
  CHECK(scene->warnings[0].find("2 mesh vertices have no normal") == 0);
  const auto shading_normal_at = [&](float x) {
    Ray r;
    r.origin = {x, 0.25f, 1.0f};
    r.direction = {0, 0, -1};
    r.t_min = 0.0f;
    r.t_max = 1e30f;
    const auto hit = scene->geometry.intersect(r);
    REQUIRE(hit);
    return hit->shading_normal;
  };
  for (const float x : {0.25f, 2.25f}) {  // the NaN and the zero corner: flat, the geometric normal
    CAPTURE(x);
    const Vec3 n = shading_normal_at(x);
    CHECK(n.x == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(n.z == doctest::Approx(1.0));
  }
  const Vec3 n = shading_normal_at(4.25f);  // all three normals: interpolated as before
  CHECK(n.x == doctest::Approx(0.6));
  CHECK(n.z == doctest::Approx(0.8));
}

}  // namespace pbrt_geometry_test
