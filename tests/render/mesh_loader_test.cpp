// OBJ and PLY loading: the meshes that come out, the errors bad files give, and no crash on garbage.
// The files are written by the tests themselves, so every expected number below is exact by construction.
#include <doctest/doctest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "test_support.h"
#include "render/scene/mesh_loader.h"
#include "render/scene/obj_loader.h"
#include "render/scene/ply_loader.h"
#include "spectral/error.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// A folder of its own per test case, removed afterwards.
struct TempDir : test::ScratchFolder {
  TempDir() : ScratchFolder("mesh_loader") {}
};

// Runs `load`, expecting an InputError whose message holds every fragment; returns the error's location.
SourceLocation expect_input_error(const std::function<void()>& load, std::initializer_list<std::string> fragments) {
  try {
    load();
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& fragment : fragments)
      CHECK_MESSAGE(message.find(fragment) != std::string::npos, message, " lacks ", fragment);
    return e.where();
  }
  FAIL("no InputError; expected one mentioning ", *fragments.begin());
  return {};
}

// Twice the signed area of triangle t projected on the xy plane (positive = counter-clockwise seen from +z).
double signed_area2_xy(const TriangleMesh& m, size_t t) {
  const Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
             c = m.positions[m.indices[3 * t + 2]];
  return double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x);
}

// ---- PLY files -------------------------------------------------------------------------------------------

enum class PlyFormat { ascii, little, big };

// Appends a binary value in the file's byte order.
template <typename T>
void put(std::string& out, T value, PlyFormat format) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if ((format == PlyFormat::big) == (std::endian::native == std::endian::little))
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  out.append(raw, sizeof(T));
}

// A unit square (quad 0 1 2 3) and a triangle (0 1 4) with normals and (s, t) uvs, plus properties and an
// element the loader must skip: a uchar colour and a list in each vertex, an int before the face's index list,
// and a trailing 'edge' element. Vertex 1's normal has length 2 (the loader normalises it); vertex 4's z is
// the double 0.1 (rounded to float on load).
struct PlyVertex {
  float x, y;
  double z;
  unsigned char red;
  float nx, ny, nz, s, t;
};
const PlyVertex kVertices[] = {
    {0, 0, 0, 10, 0, 0, 1, 0, 0},
    {1, 0, 0, 20, 0, 0, 2, 1, 0},
    {1, 1, 0, 30, 0, 0, 1, 1, 1},
    {0, 1, 0, 40, 0, 0, 1, 0, 1},
    {0.5f, 0.5f, 0.1, 50, 0, -1, 1, 0.5f, 0.25f},
};

std::string ply_file(PlyFormat format, const std::vector<std::vector<int>>& faces = {{0, 1, 2, 3}, {0, 1, 4}}) {
  const char* name = format == PlyFormat::ascii    ? "ascii"
                     : format == PlyFormat::little ? "binary_little_endian"
                                                   : "binary_big_endian";
  // Built with += (a chain of + on a string literal trips GCC 12's false -Wrestrict warning).
  std::string out = "ply\nformat ";
  out += name;
  out +=
      " 1.0\ncomment written by rimu's mesh loader test\n"
      "element vertex 5\nproperty float x\nproperty float y\nproperty double z\nproperty uchar red\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n"
      "property list uchar int extra\nelement face ";
  out += std::to_string(faces.size());
  out +=
      "\nproperty int flags\nproperty list uchar uint vertex_indices\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  if (format == PlyFormat::ascii) {
    for (const PlyVertex& v : kVertices)
      out += std::to_string(v.x) + " " + std::to_string(v.y) + " " + (v.z == 0.1 ? "0.1" : std::to_string(v.z)) + " " +
             std::to_string(v.red) + " " + std::to_string(v.nx) + " " + std::to_string(v.ny) + " " +
             std::to_string(v.nz) + " " + std::to_string(v.s) + " " + std::to_string(v.t) + " 2 7 8\n";
    for (const auto& f : faces) {
      out += "9 ";  // the flags property, then the index list
      out += std::to_string(f.size());
      for (int i : f) out += ' ' + std::to_string(i);
      out += '\n';
    }
    out += "0 1\n";
    return out;
  }
  for (const PlyVertex& v : kVertices) {
    put(out, v.x, format), put(out, v.y, format), put(out, v.z, format), put(out, v.red, format);
    put(out, v.nx, format), put(out, v.ny, format), put(out, v.nz, format), put(out, v.s, format),
        put(out, v.t, format);
    put(out, uint8_t{2}, format), put(out, int32_t{7}, format), put(out, int32_t{8}, format);
  }
  for (const auto& f : faces) {
    put(out, int32_t{9}, format), put(out, static_cast<uint8_t>(f.size()), format);
    for (int i : f) put(out, static_cast<uint32_t>(i), format);
  }
  put(out, int32_t{0}, format), put(out, int32_t{1}, format);
  return out;
}

// The header above is 21 lines, so an ascii body's first line (vertex 0) is line 22.
constexpr int kPlyBodyLine = 22;

}  // namespace

TEST_CASE("PLY ascii, binary little-endian and binary big-endian files give the same mesh") {
  TempDir dir;
  for (PlyFormat format : {PlyFormat::ascii, PlyFormat::little, PlyFormat::big}) {
    CAPTURE(static_cast<int>(format));
    const TriangleMesh mesh = load_mesh(dir.write("square.ply", ply_file(format)));
    REQUIRE(mesh.positions.size() == 5);
    REQUIRE(mesh.normals.size() == 5);
    REQUIRE(mesh.uvs.size() == 5);
    // The quad is fanned from its first corner: (0 1 2) and (0 2 3); then the triangle (0 1 4).
    CHECK(mesh.indices == std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 4});
    CHECK(mesh.positions[2] == Vec3(1, 1, 0));
    CHECK(mesh.positions[4] == Vec3(0.5f, 0.5f, 0.1f));                   // the double 0.1 rounded to the nearest float
    CHECK(mesh.normals[1] == Vec3(0, 0, 1));                              // (0, 0, 2) normalised
    CHECK(mesh.normals[4].y == static_cast<float>(-1 / std::sqrt(2.0)));  // (0, -1, 1) normalised in double
    CHECK(mesh.uvs[4].x == 0.5f);
    CHECK(mesh.uvs[4].y == 0.25f);
    CHECK(mesh.validate().empty());
  }
}

TEST_CASE("PLY polygons are fan-triangulated and the alternative property names are read") {
  TempDir dir;
  // A convex pentagon as vertex_index with texture_u/texture_v and no normals.
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
      "property float texture_u\nproperty float texture_v\nelement face 1\nproperty list uint8 int32 vertex_index\n"
      "end_header\n0 0 0 0 0\n2 0 0 1 0\n3 1 0 1 1\n1 2 0 0 1\n-1 1 0 0.5 0.5\n5 0 1 2 3 4\n";
  const TriangleMesh mesh = load_ply(dir.write("pentagon.ply", text));
  CHECK(mesh.normals.empty());
  REQUIRE(mesh.uvs.size() == 5);
  CHECK(mesh.uvs[2].y == 1.0f);
  CHECK(mesh.indices == std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4});
  // The shoelace area of the pentagon is 5; the fan covers it exactly, all triangles counter-clockwise.
  double area2 = 0.0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    CHECK(signed_area2_xy(mesh, t) > 0.0);
    area2 += signed_area2_xy(mesh, t);
  }
  CHECK(area2 == 10.0);
}

TEST_CASE("PLY errors name the file and the header line or the element and record") {
  TempDir dir;
  const std::string good = ply_file(PlyFormat::ascii);
  auto with = [&good](const std::string& from, const std::string& to) {
    std::string s = good;
    const size_t at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
  };
  auto load = [&dir](const std::string& bytes) { return [&dir, bytes] { load_ply(dir.write("bad.ply", bytes)); }; };

  CHECK(expect_input_error(load("solid cube\n"), {"bad.ply:1", "not a PLY file"}).line == 1);
  CHECK(expect_input_error(load(with("ascii 1.0", "binary_middle_endian 1.0")), {"bad.ply:2", "binary_middle_endian"})
            .line == 2);
  CHECK(expect_input_error(load(with("ascii 1.0", "ascii 2.0")), {"bad.ply:2", "version"}).line == 2);
  CHECK(expect_input_error(load(with("property double z", "property float128 z")), {"bad.ply:7", "float128"}).line ==
        7);
  CHECK(expect_input_error(load(with("property float x", "property float w")), {"bad.ply:4", "no property 'x'"}).line ==
        4);
  expect_input_error(load(good.substr(0, good.find("end_header"))), {"bad.ply", "end_header"});
  expect_input_error(load("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float "
                          "z\nend_header\n"),
                     {"bad.ply", "no 'face' element"});
  expect_input_error(load(with("element vertex 5", "element vertex five")), {"bad.ply:4", "five"});

  // Body errors in ascii carry the body line; the faces start on line kPlyBodyLine + 5.
  CHECK(expect_input_error(load(with("9 3 0 1 4", "9 3 0 1 7")),
                           {"bad.ply", "face 1", "refers to vertex 7 but there are 5 vertices"})
            .line == kPlyBodyLine + 6);
  CHECK(expect_input_error(load(with("9 3 0 1 4", "9 2 0 1")), {"bad.ply", "face 1", "has 2 vertices"}).line ==
        kPlyBodyLine + 6);
  const std::string vertex2 = "1.000000 1.000000 0";
  CHECK(expect_input_error(load(with(vertex2, "1.000000 nan 0")), {"bad.ply", "vertex 2", "not finite"}).line ==
        kPlyBodyLine + 2);
  CHECK(expect_input_error(load(with(vertex2, "1.000000 1e39 0")), {"bad.ply", "vertex 2", "not finite"}).line ==
        kPlyBodyLine + 2);
  CHECK(expect_input_error(load(with(vertex2, "1.000000 one 0")), {"bad.ply", "vertex 2", "expected a number"}).line ==
        kPlyBodyLine + 2);
  expect_input_error(load(with("9 4 0 1 2 3", "9 4 0 1 2 3.5")), {"bad.ply", "face 0", "integer type"});
  expect_input_error(load(good.substr(0, good.size() - 9)), {"bad.ply", "face 1", "truncated"});

  // Binary: the same checks by element and record, with the byte offset instead of a line.
  std::string binary = ply_file(PlyFormat::little, {{0, 1, 2, 3}, {0, 1, 2048}});
  const SourceLocation where =
      expect_input_error(load(binary), {"bad.ply", "face 1", "refers to vertex 2048 but there are 5 vertices", "byte"});
  CHECK(where.line == 0);
  // A vertex record is x y (4 + 4), z (8), red (1), nx ny nz s t (5 * 4) and the list (1 + 2 * 4): 46 bytes.
  std::string nan_vertex = ply_file(PlyFormat::big), nan_bytes;
  put(nan_bytes, std::nanf(""), PlyFormat::big);
  nan_vertex.replace(nan_vertex.find("end_header\n") + 11 + 3 * 46 + 4, 4, nan_bytes);  // vertex 3's y
  expect_input_error(load(nan_vertex), {"bad.ply", "vertex 3", "not finite"});
  expect_input_error(load(binary.substr(0, binary.size() - 20)), {"bad.ply", "face 1", "truncated"});
  expect_input_error([&] { load_ply(dir.path / "missing.ply"); }, {"missing.ply", "cannot open"});
}

TEST_CASE("PLY normals that are zero or NaN load as (0, 0, 0), no normal at that vertex, and validate() passes") {
  // Exporters write NaN where a vertex's normal is undefined (Bitterli's lamp); pbrt-v4 loads such files and shades
  // the triangles there flat, so Rimu reads them rather than refusing the file (its error until then).
  TempDir dir;
  const std::string good = ply_file(PlyFormat::ascii);
  for (const char* normal : {"0.000000 0.000000 0.000000", "nan nan nan", "0.000000 inf 0.000000"}) {
    CAPTURE(normal);
    std::string text = good;
    const std::string vertex2 = "0.000000 0.000000 1.000000 1.000000 1.000000";  // its nx ny nz s t
    REQUIRE(text.find(vertex2) != std::string::npos);
    text.replace(text.find(vertex2), vertex2.size(), std::string(normal) + " 1.000000 1.000000");
    const TriangleMesh mesh = load_ply(dir.write("odd.ply", text));
    REQUIRE(mesh.normals.size() == 5);
    CHECK(mesh.normals[2].x == 0.0f);
    CHECK(mesh.normals[2].y == 0.0f);
    CHECK(mesh.normals[2].z == 0.0f);
    CHECK(mesh.normals[1].z == 1.0f);
    CHECK(mesh.vertices_without_normal() == 1);
    CHECK(mesh.validate().empty());
  }
}

TEST_CASE("PLY degenerate triangles are kept, validate() passes, and the scene can remove them") {
  TempDir dir;
  // Triangle (0 1 2) of the square plus a zero-area triangle (0 1 1) that repeats a vertex.
  const TriangleMesh mesh = load_ply(dir.write("degenerate.ply", ply_file(PlyFormat::little, {{0, 1, 2}, {0, 1, 1}})));
  CHECK(mesh.triangle_count() == 2);
  CHECK(mesh.validate().empty());
  TriangleMesh cleaned = mesh;
  CHECK(cleaned.remove_degenerate_triangles() == 1);
}

TEST_CASE("truncated PLY files load only when complete and otherwise give an InputError, never a crash") {
  // In memory (parse_ply is load_ply after reading the file): a file write per length would take seconds.
  for (PlyFormat format : {PlyFormat::ascii, PlyFormat::little, PlyFormat::big}) {
    const std::string whole = ply_file(format);
    for (size_t length = 0; length <= whole.size(); ++length) {
      CAPTURE(length);
      bool loaded = false;
      try {
        loaded = parse_ply(whole.substr(0, length), "truncated.ply").validate().empty();
      } catch (const InputError&) {
      }
      // Binary: every byte is needed. Ascii: dropping the final newline still leaves the last number whole.
      const size_t shortest = format == PlyFormat::ascii ? whole.size() - 1 : whole.size();
      CHECK(loaded == (length >= shortest));
    }
  }
}

TEST_CASE("garbled PLY files load a valid mesh or give an InputError, never a crash") {
  // Every byte of each file set to a few troublesome values, then random multi-byte damage (fixed seed).
  std::mt19937 random(20240611u);
  int loaded = 0, rejected = 0;
  for (PlyFormat format : {PlyFormat::ascii, PlyFormat::little, PlyFormat::big}) {
    const std::string whole = ply_file(format);
    auto attempt = [&](const std::string& bytes) {
      try {
        const TriangleMesh mesh = parse_ply(bytes, "garbled.ply");
        CHECK(mesh.validate().empty());
        ++loaded;
      } catch (const InputError&) {
        ++rejected;
      }
    };
    for (size_t i = 0; i < whole.size(); ++i)
      for (char value : {'\0', '\xff', '\x7f', '\n', ' ', '9'}) {
        std::string bytes = whole;
        bytes[i] = value;
        attempt(bytes);
      }
    for (int trial = 0; trial < 300; ++trial) {
      std::string bytes = whole;
      for (int k = 0; k < 4; ++k) bytes[random() % bytes.size()] = static_cast<char>(random() & 0xff);
      attempt(bytes);
    }
  }
  // Both outcomes occur: the fuzzing reaches past the header into the body.
  CHECK(loaded > 0);
  CHECK(rejected > 0);
}

// ---- OBJ files -------------------------------------------------------------------------------------------

TEST_CASE("OBJ quads are triangulated and (position, uv, normal) corners are de-indexed") {
  TempDir dir;
  // A unit square in z = 0 facing +z: 4 positions, 4 uvs, 1 normal shared by all corners.
  const std::string text =
      "# square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 3\n"
      "f 1/1/1 2/2/1 3/3/1 4/4/1\n";
  const TriangleMesh mesh = load_obj(dir.write("square.obj", text));
  CHECK(mesh.triangle_count() == 2);
  CHECK(mesh.positions.size() == 4);  // each corner (p, t, n) is distinct, and each is used twice at most
  REQUIRE(mesh.normals.size() == 4);
  REQUIRE(mesh.uvs.size() == 4);
  for (size_t v = 0; v < 4; ++v) {
    CHECK(mesh.normals[v] == Vec3(0, 0, 1));      // (0, 0, 3) normalised
    CHECK(mesh.uvs[v].x == mesh.positions[v].x);  // this square's uvs equal its xy
    CHECK(mesh.uvs[v].y == mesh.positions[v].y);
  }
  // Whichever diagonal tinyobjloader splits along, the two triangles keep the quad's winding and cover it.
  CHECK(signed_area2_xy(mesh, 0) == 1.0);
  CHECK(signed_area2_xy(mesh, 1) == 1.0);
  CHECK(mesh.validate().empty());
}

TEST_CASE("OBJ corners that share a position but not a normal become separate vertices") {
  TempDir dir;
  // Two triangles on a crease: positions 1 and 3 are shared, but each triangle has its own normal, so the
  // de-indexed mesh has 6 vertices; with a shared normal it has 4.
  const std::string positions = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nvn 0 0 1\nvn 0 -1 1\n";
  const TriangleMesh crease = load_obj(dir.write("crease.obj", positions + "f 1//1 2//1 3//1\nf 1//2 3//2 4//2\n"));
  CHECK(crease.positions.size() == 6);
  CHECK(crease.triangle_count() == 2);
  const TriangleMesh smooth = load_obj(dir.write("smooth.obj", positions + "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n"));
  CHECK(smooth.positions.size() == 4);
  CHECK(smooth.indices == std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
  // Relative indices count back from the statements read so far: -4 is the first of 4 vertices.
  const TriangleMesh relative = load_obj(dir.write("relative.obj", positions + "f -4//-2 -3//-2 -2//-2\n"));
  CHECK(relative.positions.size() == 3);
  CHECK(relative.positions[0] == Vec3(0, 0, 0));
}

TEST_CASE("OBJ concave polygons are triangulated by ear clipping into same-winding triangles") {
  TempDir dir;
  // An L-shaped hexagon of area 3, starting at its reflex corner (1, 1).
  const TriangleMesh mesh =
      load_obj(dir.write("l.obj", "v 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4 5 6\n"));
  REQUIRE(mesh.triangle_count() == 4);
  double area2 = 0.0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    CHECK(signed_area2_xy(mesh, t) > 0.0);
    area2 += signed_area2_xy(mesh, t);
  }
  CHECK(area2 == 6.0);
}

TEST_CASE("OBJ objects can be loaded alone, and normals missing on some faces become flat normals") {
  TempDir dir;
  const fs::path file = dir.write("two.obj",
                                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n"
                                  "o smooth\nf 1//1 2//1 3//1\no flat\nf 1 4 2\n");
  const TriangleMesh all = load_obj(file);
  CHECK(all.triangle_count() == 2);
  REQUIRE(all.normals.size() == all.positions.size());
  // Triangle (0,0,0) (0,0,1) (1,0,0) lies in y = 0 and turns counter-clockwise seen from +y.
  CHECK(all.normals[all.indices[3]] == Vec3(0, 1, 0));
  CHECK(all.validate().empty());

  const TriangleMesh flat = load_mesh(file, "flat");
  CHECK(flat.triangle_count() == 1);
  CHECK(flat.normals.empty());
  CHECK(flat.positions[1] == Vec3(0, 0, 1));
  expect_input_error([&] { load_obj(file, "round"); }, {"two.obj", "'round'", "'flat'", "'smooth'"});
}

TEST_CASE("OBJ errors name the file and the line") {
  TempDir dir;
  auto load = [&dir](const std::string& text) { return [&dir, text] { load_obj(dir.write("bad.obj", text)); }; };
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  CHECK(expect_input_error(load("v 0 0 0\nv 1 abc 0\n"), {"bad.obj:2", "'abc' is not a finite number"}).line == 2);
  CHECK(expect_input_error(load("v 0 0 0\r\nv 1 0 0\r\nv 1 1e39 0\r\n"), {"bad.obj:3", "not a finite number"}).line ==
        3);
  CHECK(expect_input_error(load("v 0 0 0\nv 1 nan 0\n"), {"bad.obj:2", "not a finite number"}).line == 2);
  CHECK(expect_input_error(load("v 0 0\n"), {"bad.obj:1", "needs at least 3 numbers"}).line == 1);
  CHECK(expect_input_error(load(quad + "f 1 2 9\n"), {"bad.obj:5", "refers to vertex 9 but the file has 4"}).line == 5);
  CHECK(expect_input_error(load(quad + "f 0 1 2\n"), {"bad.obj:5", "start at 1"}).line == 5);
  CHECK(expect_input_error(load("v 0 0 0\nf -1 -2 -3\n" + quad), {"bad.obj:2", "back but only 1"}).line == 2);
  CHECK(expect_input_error(load(quad + "vt 0 0\nf 1/2 2/1 3/1\n"), {"bad.obj:6", "texture coordinate 2"}).line == 6);
  CHECK(expect_input_error(load(quad + "f 1 2\n"), {"bad.obj:5", "at least 3 corners"}).line == 5);
  CHECK(expect_input_error(load(quad + "f 1/x 2 3\n"), {"bad.obj:5", "'x' is not an index"}).line == 5);
  CHECK(expect_input_error(load(quad + "vn 0 0 0\nf 1//1 2//1 3//1\n"), {"bad.obj:5", "zero"}).line == 5);
  // tinyobjloader's own errors are passed on with their line.
  CHECK(expect_input_error(load(quad + "l 0 1\n"), {"bad.obj:5", "tinyobjloader"}).line == 5);
  expect_input_error(load(quad), {"bad.obj", "no faces"});
  expect_input_error([&] { load_obj(dir.path / "missing.obj"); }, {"missing.obj", "cannot open"});
}

TEST_CASE("OBJ degenerate triangles are kept and validate() passes") {
  TempDir dir;
  // Collinear points, and a triangle repeating a vertex; one normal-less face so the flat-normal path sees them.
  const TriangleMesh mesh = load_obj(dir.write("degenerate.obj",
                                               "v 0 0 0\nv 1 0 0\nv 2 0 0\nvn 0 0 1\n"
                                               "f 1//1 2//1 3//1\nf 1 2 2\n"));
  CHECK(mesh.triangle_count() == 2);
  CHECK(mesh.validate().empty());
  TriangleMesh cleaned = mesh;
  CHECK(cleaned.remove_degenerate_triangles() == 2);
}

TEST_CASE("truncated and garbled OBJ text loads a valid mesh or gives an InputError, never a crash") {
  const std::string whole =
      "o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n"
      "f 1/1/1 2/2/1 3/2/1 4/1/1\nf -4/-2/-1 -2/-1/-1 -1/-1/-1\n";
  std::mt19937 random(7u);
  auto attempt = [](const std::string& text) {
    try {
      const TriangleMesh mesh = parse_obj(text, "garbled.obj");
      CHECK(mesh.validate().empty());
    } catch (const InputError&) {
    }
  };
  for (size_t length = 0; length <= whole.size(); ++length) attempt(whole.substr(0, length));
  for (int trial = 0; trial < 500; ++trial) {
    std::string text = whole;
    for (int k = 0; k < 3; ++k) text[random() % text.size()] = "0123456789-/ \nvtnf.e"[random() % 20];
    attempt(text);
  }
}

TEST_CASE("load_mesh dispatches on the extension, case-insensitively") {
  TempDir dir;
  CHECK(load_mesh(dir.write("TRI.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).triangle_count() == 1);
  const fs::path ply = dir.write("square.PLY", ply_file(PlyFormat::ascii));
  CHECK(load_mesh(ply).triangle_count() == 3);
  expect_input_error([&] { load_mesh(ply, "square"); }, {"square.PLY", "single mesh"});
  expect_input_error([&] { load_mesh(dir.write("cube.stl", "solid")); }, {"cube.stl", "'.stl'", ".obj, .ply"});
}

TEST_CASE("triangle mesh: pbrt's front, by the shading normals or the winding, reversed, and pbrt's default uvs") {
  // Two triangles of the unit square facing +z by their winding; the second's normals point to −z.
  rimu::TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  const auto facing_z = [](const rimu::TriangleMesh& m, size_t t) {
    const uint32_t* i = &m.indices[3 * t];
    return cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]).z;
  };
  SUBCASE("without normals: the winding; reversed flips every triangle") {
    rimu::TriangleMesh m = mesh;
    CHECK(m.turn_to_pbrt_front(false) == 0);
    CHECK(m.turn_to_pbrt_front(true) == 2);
    CHECK(facing_z(m, 0) < 0);
    CHECK(facing_z(m, 1) < 0);
  }
  SUBCASE("with normals: the side they point to; a corner without one leaves the winding") {
    rimu::TriangleMesh m = mesh;
    m.positions.insert(m.positions.end(), {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}});
    m.indices.insert(m.indices.end(), {4, 5, 6});  // a third triangle, facing +z by its winding
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 0}, {0, 0, -1}, {0, 0, -1}, {0, 0, -1}};
    rimu::TriangleMesh r = m;
    CHECK(m.turn_to_pbrt_front(false) == 1);  // only the third, whose normals point to −z
    CHECK(facing_z(m, 0) > 0);
    CHECK(facing_z(m, 1) > 0);  // vertex 3 has no normal: the winding
    CHECK(facing_z(m, 2) < 0);
    CHECK(r.turn_to_pbrt_front(true) == 2);  // reversed: normals negated; the second by its reversed winding
    CHECK(r.normals[0].z < 0);
    CHECK(facing_z(r, 0) < 0);
    CHECK(facing_z(r, 1) < 0);
    CHECK(facing_z(r, 2) > 0);
  }
  SUBCASE("pbrt's default uvs survive a rewind: the corners get their own vertices with the uvs of the order read") {
    rimu::TriangleMesh m = mesh;
    m.default_uvs = rimu::TriangleMesh::DefaultUvs::pbrt;
    const rimu::Vec2 before = m.uv_at(1, 0.25f, 0.5f);  // the second triangle, at barycentrics (0.25, 0.5)
    CHECK(m.turn_to_pbrt_front(true) == 2);
    CHECK(m.positions.size() == 6);
    CHECK(m.uvs.size() == 6);
    // Rewinding swapped corners 1 and 2, so the same point now has barycentrics (0.5, 0.25).
    const rimu::Vec2 after = m.uv_at(1, 0.5f, 0.25f);
    CHECK(after.x == doctest::Approx(before.x));
    CHECK(after.y == doctest::Approx(before.y));
  }
}
