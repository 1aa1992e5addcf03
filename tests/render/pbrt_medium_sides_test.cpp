// Which side of a pbrt shape its media are on (src/render/scene/pbrt/pbrt_media.cpp, docs/pbrt-import.md "Media"):
// pbrt-v4 puts a MediumInterface's interior behind the surface normal and its exterior in front. Every case is
// checked against a twin written the other way round (normals flipped by ReverseOrientation or by the winding, and
// the two media swapped), which pbrt-v4 renders identically: the imported documents must be identical too.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "pbrt_test_support.h"
#include "render/scene/scene.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_medium_sides_test {

const std::string kFog = "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_s\" [2 2 2] \"rgb sigma_a\" [0.5 0.5 0.5]\n";
const std::string kCamera = "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\n";

// The unit cube [-1, 1]³ as 12 triangles, counter-clockwise seen from outside (normals out) unless `inward`.
std::string cube(bool inward) {
  static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::string indices;
  for (const auto& f : faces) {
    const int quad[6] = {f[0], f[1], f[2], f[0], f[2], f[3]};
    for (int k = 0; k < 6; k += 3) {
      const int a = quad[k], b = quad[k + (inward ? 2 : 1)], c = quad[k + (inward ? 1 : 2)];
      indices += std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "  ";
    }
  }
  // Vertex i has x = ±1 by bit 0, y by bit 1, z by bit 2.
  return "Shape \"trianglemesh\" \"point3 P\" [-1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1  -1 -1 1  1 -1 1  -1 1 1  1 1 1] "
         "\"integer indices\" [" + indices + "]\n";
}

// A square in z = 0, its normal +z (or −z when `down`).
std::string square(bool down) {
  return std::string("Shape \"trianglemesh\" \"point3 P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] \"integer indices\" ") +
         (down ? "[0 2 1  0 3 2]\n" : "[0 1 2  0 2 3]\n");
}

PbrtImport import_world(const std::string& camera_medium, const std::string& world) {
  return test::import_pbrt_test_text(kFog + camera_medium + kCamera + "WorldBegin\n" + world, "sides.pbrt");
}

// What renders from a document, however its triangles were written: the media, the materials, and each shape's
// material and triangles as position triples (each rotated to start at its smallest vertex, which keeps its
// winding), sorted. (Twins may differ in how vertices are shared and in pbrt's per-triangle default uv, which no
// texture here reads.)
json document_of(const PbrtImport& imported) {
  const json& d = imported.document;
  using Triangle = std::array<std::array<double, 3>, 3>;
  json shapes = json::array();
  for (const json& shape : d["shapes"]) {
    std::vector<Triangle> triangles;
    const json& indices = shape["indices"];
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
      Triangle triangle;
      for (size_t k = 0; k < 3; ++k) triangle[k] = shape["positions"][indices[t + k].get<size_t>()].get<std::array<double, 3>>();
      std::rotate(triangle.begin(), std::min_element(triangle.begin(), triangle.end()), triangle.end());
      triangles.push_back(triangle);
    }
    std::sort(triangles.begin(), triangles.end());
    shapes.push_back({{"material", shape["material"]}, {"triangles", triangles}});
  }
  return {{"shapes", shapes}, {"media", d.value("media", json::object())}, {"materials", d["materials"]}};
}

// The geometric normal of a shape's first triangle (Rimu's front: counter-clockwise).
std::array<double, 3> first_normal(const json& shape) {
  std::array<std::array<double, 3>, 3> p;
  for (size_t k = 0; k < 3; ++k) p[k] = shape["positions"][shape["indices"][k].get<size_t>()].get<std::array<double, 3>>();
  const std::array<double, 3> e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
  const std::array<double, 3> e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  return {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
}

TEST_CASE("pbrt medium sides: a cube facing inward with MediumInterface \"\" \"fog\" is filled with fog, as its twins") {
  // The cube's interface faces point outward with fog inside (the plain way); the twins point inward, by
  // ReverseOrientation or by their winding, with fog outside, i.e. on the side their normals point to: the inside.
  const PbrtImport plain = import_world("", "AttributeBegin\nMediumInterface \"fog\" \"\"\nMaterial \"interface\"\n" + cube(false) + "AttributeEnd\n");
  const PbrtImport reversed = import_world(
      "", "AttributeBegin\nMediumInterface \"\" \"fog\"\nMaterial \"interface\"\nReverseOrientation\n" + cube(false) + "AttributeEnd\n");
  const PbrtImport wound = import_world("", "AttributeBegin\nMediumInterface \"\" \"fog\"\nMaterial \"interface\"\n" + cube(true) + "AttributeEnd\n");
  for (const PbrtImport* imported : {&plain, &reversed, &wound}) {
    CHECK_MESSAGE(imported->ignored.empty(), describe_ignored(imported->ignored));
    const json& d = imported->document;
    REQUIRE(d["media"].contains("fog"));
    CHECK(d["media"]["fog"]["index_matched"] == true);
    CHECK(d["shapes"][0]["material"] == d["media"]["fog"]["boundary_material"]);
    const auto scene = load_scene(d, "sides.pbrt", test::test_data("pbrt"), test::library());
    CHECK(scene->camera_medium == -1);  // the camera, outside the cube, is in vacuum
  }
  // Identical documents: the same triangles, wound outward, bounding the same medium.
  CHECK(document_of(reversed) == document_of(plain));
  CHECK(document_of(wound) == document_of(plain));
}

TEST_CASE("pbrt medium sides: an interface plane with fog in front bounds it from behind, as its twin") {
  // Fog above the plane (its front, +z) against the twin facing down with fog behind it (again above).
  const PbrtImport front = import_world("", "MediumInterface \"\" \"fog\"\nMaterial \"interface\"\n" + square(false));
  const PbrtImport behind = import_world("", "MediumInterface \"fog\" \"\"\nMaterial \"interface\"\n" + square(true));
  CHECK(front.ignored.empty());
  CHECK(behind.ignored.empty());
  CHECK(document_of(front) == document_of(behind));
  // Rimu's front (counter-clockwise) now faces down: a path crossing downward leaves the fog, upward enters it.
  CHECK(first_normal(front.document["shapes"][0])[2] < 0);
}

TEST_CASE("pbrt medium sides: an opaque room facing inward holds the camera's fog, an open opaque floor is listed") {
  // The room's walls face inward with fog in front; the twin faces outward with fog inside. The camera is in fog.
  const PbrtImport inward = import_world("MediumInterface \"\" \"fog\"\n",
                                         "MediumInterface \"\" \"fog\"\nMaterial \"diffuse\"\n" + cube(true));
  const PbrtImport outward = import_world("MediumInterface \"\" \"fog\"\n",
                                          "MediumInterface \"fog\" \"\"\nMaterial \"diffuse\"\n" + cube(false));
  CHECK(inward.ignored.empty());
  CHECK(document_of(inward) == document_of(outward));
  CHECK(inward.document["media"]["fog"]["contains_camera"] == true);
  CHECK(inward.document["media"]["fog"].contains("boundary_material"));
  // An open opaque floor with fog only in front: pbrt gives just the rays leaving it the fog; not represented.
  const PbrtImport floor = import_world("", "MediumInterface \"\" \"fog\"\nMaterial \"diffuse\"\n" + square(false));
  CHECK_CONTAINS(describe_ignored(floor.ignored), "an open opaque shape with a medium only in front of it",
                 "first at sides.pbrt:8");
  CHECK(first_normal(floor.document["shapes"][0])[2] > 0);  // left as written
}

TEST_CASE("pbrt medium sides: spheres and PLY meshes with fog in front are turned like any mesh") {
  // A whole sphere with fog in front takes the mesh path (Rimu's analytic sphere cannot be turned inside out).
  const PbrtImport sphere = import_world("", "MediumInterface \"\" \"fog\"\nMaterial \"interface\"\nShape \"sphere\"\n");
  CHECK(sphere.ignored.empty());
  const json& s = sphere.document["shapes"][0];
  REQUIRE(s["type"] == "triangles");
  CHECK(s["material"] == sphere.document["media"]["fog"]["boundary_material"]);
  // Turned: the normals point to the centre.
  const auto p = s["positions"][100].get<std::array<double, 3>>();
  const auto n = s["normals"][100].get<std::array<double, 3>>();
  CHECK(p[0] * n[0] + p[1] * n[1] + p[2] * n[2] < 0);
  // quad.ply (the unit square, normal +z) with fog in front stays a file, turned by the loader ("reversed").
  const PbrtImport ply = import_world("", "MediumInterface \"\" \"fog\"\nMaterial \"interface\"\nShape \"plymesh\" \"string filename\" \"quad.ply\"\n");
  CHECK(ply.ignored.empty());
  CHECK(ply.document["shapes"][0]["type"] == "mesh");
  CHECK(ply.document["shapes"][0]["front"] == "pbrt");
  CHECK(ply.document["shapes"][0]["reversed"] == true);
  CHECK(ply.document["shapes"][0]["material"] == ply.document["media"]["fog"]["boundary_material"]);
}

}  // namespace pbrt_medium_sides_test
