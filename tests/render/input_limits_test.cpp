// Hostile inputs to the scene loader and its file readers: each is an InputError that names the file and the line or
// key, never a crash, a hang, an unbounded allocation or a silent loss (docs/scene-format.md, "Limits").
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "test_support.h"
#include "input_error_check.h"
#include "integration_support.h"
#include "render/scene/coordinate_limit.h"
#include "render/scene/ies_file.h"
#include "render/scene/json_cursor.h"
#include "render/scene/light_definition.h"
#include "render/scene/obj_check.h"
#include "render/scene/obj_loader.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"
#include "transport/media/grid_medium.h"

using namespace rimu;
using nlohmann::json;
using namespace std::string_literals;
namespace fs = std::filesystem;
using test::input_error;

namespace {

// A folder of its own per test case, removed afterwards.
struct TempDir : test::ScratchFolder {
  TempDir() : ScratchFolder("input_limits") {}
};

json one_sphere_scene() {
  return json::parse(R"({
    "camera": {"from": [0, 0, -3], "to": [0, 0, 0]},
    "film": {"resolution": [4, 4]},
    "materials": {"white": {"type": "diffuse", "reflectance": 0.8}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}],
    "lights": [{"type": "environment", "radiance": 1}]
  })");
}

InputError scene_error(const json& scene, const std::string& key, std::initializer_list<std::string> fragments) {
  const InputError e = input_error([&] { test::scene_from_json(scene, "hostile.json"); }, fragments);
  CHECK(e.where().file == "hostile.json");
  CHECK(e.where().key == key);
  return e;
}

}  // namespace

TEST_CASE("input limits: coordinates beyond Embree's range are refused at the key that sets them") {
  // Embree asserts on a ray origin beyond ±1.844e18 (a camera at 2e18 m aborted the process) and silently drops
  // geometry there; Rimu's limit is 1e18 m.
  json s = one_sphere_scene();
  s["camera"]["from"] = {0.0, 0.0, -2e18};
  scene_error(s, "/camera/from", {"camera position", "1e+18"});
  s["camera"]["from"] = {0.0, 0.0, -1.5e18};  // inside Embree's range, outside Rimu's margin
  scene_error(s, "/camera/from", {"camera position"});

  s = one_sphere_scene();
  s["camera"]["to"] = {3e18, 0.0, 0.0};
  scene_error(s, "/camera/to", {"looks at"});

  s = one_sphere_scene();
  s["shapes"][0]["center"] = {0.0, -5e18, 0.0};
  scene_error(s, "/shapes/0/center", {"centre"});
  s = one_sphere_scene();
  s["shapes"][0]["center"] = {0.0, 9e17, 0.0};
  s["shapes"][0]["radius"] = 2e17;  // the centre is in range, the sphere's top is not
  scene_error(s, "/shapes/0/radius", {"centre ± radius"});

  // Vertices are checked after their transform.
  s = one_sphere_scene();
  s["shapes"].push_back(json::parse(R"({"type": "quad", "material": "white",
      "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], "transform": [{"translate": [0, 0, 1.2e18]}]})"));
  scene_error(s, "/shapes/1", {"vertex 0 (after the transform)"});

  // An instance: its prototype's box placed in the world, and the world seen from the prototype (where Embree
  // traces the instance's rays: a 1e-9 scale with a camera 1e10 m away aborted).
  s = one_sphere_scene();
  s["prototypes"] = json::parse(R"({"tile": [{"type": "quad", "material": "white",
      "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}]})");
  s["shapes"].push_back(json::parse(R"({"type": "instance", "prototype": "tile", "transform": [{"scale": [1e17, 1, 1]}, {"translate": [9.5e17, 0, 0]}]})"));
  scene_error(s, "/shapes/1/transform", {"prototype's bounding box"});
  s["shapes"][1]["transform"] = json::parse(R"([{"scale": 1e-9}])");
  s["camera"]["from"] = {0.0, 0.0, -1e10};
  scene_error(s, "/shapes/1/transform", {"prototype's space"});
  // A determinant below 1e-30 (here 1e-36) used to pass with the identity as its inverse.
  s["shapes"][1]["transform"] = json::parse(R"([{"scale": 1e-12}])");
  scene_error(s, "/shapes/1/transform", {"singular", "1e-36"});

  // Just inside the limit loads, renders, and discards nothing.
  s = one_sphere_scene();
  s["camera"]["from"] = {0.0, 0.0, -9e17};
  s["camera"]["vertical_fov_deg"] = 1e-3;
  s["shapes"][0]["radius"] = 1e13;
  const auto scene = test::scene_from_json(s, "far.json");
  const test::RenderedFilm rendered = test::render_xyz(*scene, 1, 1);
  CHECK(rendered.film->sample_counts().discarded() == 0);
}

TEST_CASE("input limits: each placement of an \"instances\" shape is checked at its own matrix") {
  json s = one_sphere_scene();
  s["prototypes"] = json::parse(R"({"tile": [{"type": "quad", "material": "white",
      "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}]})");
  s["shapes"].push_back(json::parse(R"({"type": "instances", "prototype": "tile", "matrices": [
      [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0], [1e17, 0, 0, 9.5e17,  0, 1, 0, 0,  0, 0, 1, 0]]})"));
  scene_error(s, "/shapes/1/matrices/1", {"prototype's bounding box"});
  // The world seen from the prototype is checked once the world is known, still at the placement's own key.
  s["shapes"][1]["matrices"][1] = {1, 0, 0, 5, 0, 1e-9, 0, 0, 0, 0, 1, 0};
  s["camera"]["from"] = {0.0, -1e10, -1.0};
  s["camera"]["to"] = {0.0, 0.0, 0.0};
  scene_error(s, "/shapes/1/matrices/1", {"prototype's space"});
  s = one_sphere_scene();
  s["prototypes"] = json::parse(R"({"tile": [{"type": "quad", "material": "white",
      "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}]})");
  s["shapes"].push_back(json::parse(R"({"type": "instances", "prototype": "tile", "matrices": [[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]]})"));
  scene_error(s, "/shapes/1/matrices/0", {"expected 12 numbers"});
  s["shapes"][1]["matrices"][0] = {1e-12, 0, 0, 0, 0, 1e-12, 0, 0, 0, 0, 1e-12, 0};
  scene_error(s, "/shapes/1/matrices/0", {"singular"});
  s["shapes"][1]["matrices"][0] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  s["shapes"][1]["prototype"] = "tiles";
  scene_error(s, "/shapes/1/prototype", {"unknown prototype 'tiles'"});
  // Two placements are two instances: a ray down the axis of the second hits it.
  s["shapes"][1]["prototype"] = "tile";
  s["shapes"][1]["matrices"].push_back({1, 0, 0, 100, 0, 1, 0, 0, 0, 0, 1, 0});
  const auto scene = test::scene_from_json(s, "instances.json");
  CHECK(scene->geometry.intersect(Ray{{100.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}}).has_value());
  CHECK_FALSE(scene->geometry.intersect(Ray{{50.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}}).has_value());
}

TEST_CASE("input limits: deep JSON nesting is refused before parsing, and error messages print a bounded value") {
  // 100 000 nested arrays where a number is expected: the dump in the message used to recurse through all of them.
  const std::string deep = std::string(100000, '[') + "1" + std::string(100000, ']');
  const std::string text = "{\n  \"camera\": {\"from\": " + deep + "}\n}\n";
  const InputError e = input_error([&] { parse_json_text(text, "deep.json"); }, {"nested more than 256"});
  CHECK(e.where().file == "deep.json");
  CHECK(e.where().line == 2);
  // Brackets inside strings do not count.
  CHECK_NOTHROW(parse_json_text("{\"a\": \"" + std::string(1000, '[') + "\"}", "strings.json"));

  // Within the limit, a wrong value's message shows a few levels and a few characters, not the whole value.
  json s = one_sphere_scene();
  json nested = 1;
  for (int i = 0; i < 200; ++i) nested = json::array({nested, 2, 3});
  s["shapes"][0]["radius"] = nested;
  const InputError r = scene_error(s, "/shapes/0/radius", {"expected a number, found array", "[...]"});
  CHECK(std::string(r.what()).size() < 300);
  json wide = json::array();
  for (int i = 0; i < 100000; ++i) wide.push_back(i);
  CHECK(json_preview(wide).size() < 100);
  CHECK(json_preview(json(std::string(100000, 'x'))).size() < 100);
  CHECK(json_preview(json{{std::string(100000, 'k'), 1}}).size() < 100);
  CHECK(json_preview(json::parse(R"({"a": [1, 2], "b": "c"})")) == R"({"a": [1, 2], "b": "c"})");
}

TEST_CASE("input limits: a NUL byte in a text file is an error at its line, not the end of the file") {
  // nlohmann's parser stopped at the NUL and ignored everything after it.
  const InputError e = input_error([] { parse_json_text("{\n  \"camera\": {},\n  \0\"shapes\": 5\n}\n"s, "nul.json"); },
                                   {"nul.json:3: column 3: a NUL byte"});
  CHECK(e.where().line == 3);
  input_error([] { obj::check_obj_text("v 0 0 0\nv 1 0 0\nv 0 1 0\0\nf 1 2 3\n"s, "nul.obj"); },
              {"nul.obj:3: column 8: a NUL byte"});
  input_error([] { parse_ies("IESNA:LM-63-2002\n\0TILT=NONE\n"s, "nul.ies"); }, {"nul.ies:2: column 1:"});
}

TEST_CASE("input limits: the scene file must be a regular file") {
  TempDir dir;
  input_error([&] { load_scene(dir.path, test::library()); }, {dir.path.string(), "is a directory"});
  input_error([&] { load_scene("/dev/zero", test::library()); }, {"/dev/zero", "character device"});
  const fs::path fifo = dir.path / "scene.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // Nobody writes to the FIFO: reading it would block for ever.
  input_error([&] { load_scene(fifo, test::library()); }, {"FIFO"});
  input_error([&] { read_ies_file(fifo); }, {"FIFO"});
  input_error([&] { load_obj(fifo); }, {"FIFO"});
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> d;
  input_error([&] { read_grid_file(fifo, nx, ny, nz, d); }, {"FIFO"});
  input_error([&] { load_scene(dir.path / "absent.json", test::library()); }, {"absent.json", "does not exist"});
  // The size limit, with a small one to test it.
  const fs::path big = dir.write("big.json", std::string(2000, ' ') + "{}");
  input_error([&] { read_input_file(big, 1000); }, {"big.json", "2002 bytes", "limit"});
  CHECK(read_input_file(big, 2002).size() == 2002);
}

TEST_CASE("input limits: an OBJ face index of -2^63 is reported without overflow") {
  // Negating -9223372036854775808 overflows a long long (UBSan); the message quotes the index as written.
  input_error([] { obj::check_obj_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n", "min.obj"); },
              {"min.obj:4:", "refers 9223372036854775808 vertices back but only 3 come before this line"});
  input_error([] { obj::check_obj_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "back.obj"); },
              {"refers 4 vertices back but only 3"});
  CHECK_NOTHROW(obj::check_obj_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", "ok.obj"));
}

TEST_CASE("input limits: an OBJ face with more corners than the limit is refused before triangulation") {
  // One face of 100 000 corners took 111 s in tinyobjloader's ear clipping; the limit is 256 corners.
  auto polygon = [](size_t corners) {
    std::string text;
    for (size_t i = 0; i < corners; ++i) {
      const double a = 6.283185307179586 * double(i) / double(corners);
      text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    text += "f";
    for (size_t i = 1; i <= corners; ++i) text += " " + std::to_string(i);
    return text + "\n";
  };
  input_error([&] { parse_obj(polygon(100000), "huge_face.obj"); },
              {"huge_face.obj:100001:", "100000 corners", "at most 256"});
  const TriangleMesh disc = parse_obj(polygon(obj::kMaxFaceCorners), "disc.obj");
  CHECK(disc.triangle_count() == obj::kMaxFaceCorners - 2);
}

TEST_CASE("input limits: a voxel grid's header is checked against the file's size before allocating") {
  // 28 bytes whose header claims 1024³ voxels (4 GiB of densities); 4096³ used to end in bad_alloc.
  TempDir dir;
  auto header = [](int32_t n) {
    std::string bytes = "RIMUVOL1";
    for (int i = 0; i < 3; ++i) bytes.append(reinterpret_cast<const char*>(&n), 4);
    return bytes;
  };
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> d;
  const fs::path short_file = dir.write("short.rvol", header(1024) + std::string(8, '\0'));
  input_error([&] { read_grid_file(short_file, nx, ny, nz, d); },
              {"short.rvol", "1024 × 1024 × 1024", "4294967316 bytes", "the file has 28 bytes"});
  CHECK(d.empty());
  input_error([&] { parse_grid_bytes(header(4096) + std::string(8, '\0'), "huge.rvol", nx, ny, nz, d); },
              {"huge.rvol", "274877906964 bytes"});
  input_error([&] { parse_grid_bytes(header(2) + std::string(33, '\0'), "long.rvol", nx, ny, nz, d); },
              {"52 bytes", "the file has 53 bytes"});
  input_error([&] { parse_grid_bytes("RIMUVOL1\1\0", "tiny.rvol", nx, ny, nz, d); }, {"not a RIMUVOL1"});
  parse_grid_bytes(header(2) + std::string(32, '\0'), "ok.rvol", nx, ny, nz, d);
  CHECK(nx == 2);
  CHECK(d.size() == 8);

  // Through a scene, the message names the scene key and the grid file.
  json s = one_sphere_scene();
  s["media"] = json::parse(R"({"fog": {"type": "grid", "file": "short.rvol", "boundary_material": "white",
      "sigma_a": 0.1, "sigma_s": 1, "bounds_min": [-1, -1, -1], "bounds_max": [1, 1, 1]}})");
  input_error([&] { load_scene(s, "fog.json", dir.path, test::library()); },
              {"fog.json: /media/fog/file: ", "short.rvol: the header announces"});
}

TEST_CASE("input limits: named spectra resolve through long chains, a real cycle is named") {
  // Nine named spectra in a chain used to be called a cycle (the depth limit was 8).
  json s = one_sphere_scene();
  s["spectra"] = json::object();
  for (int i = 0; i < 9; ++i) s["spectra"]["s" + std::to_string(i)] = {{"spectrum", "s" + std::to_string(i + 1)}};
  s["spectra"]["s9"] = 0.5;
  s["materials"]["white"]["reflectance"] = {{"spectrum", "s0"}};
  CHECK_NOTHROW(test::scene_from_json(s, "chain.json"));

  s["spectra"]["s9"] = {{"spectrum", "s4"}};
  scene_error(s, "/spectra/s9/spectrum", {"cycle: 's4' → 's5' → 's6' → 's7' → 's8' → 's9' → 's4'"});

  s["spectra"]["a"] = {{"spectrum", "a"}};
  s["materials"]["white"]["reflectance"] = {{"spectrum", "a"}};
  scene_error(s, "/spectra/a/spectrum", {"cycle: 'a' → 'a'"});

  // The depth limit is stated as what it is.
  s = one_sphere_scene();
  for (int i = 0; i < 70; ++i) s["spectra"]["s" + std::to_string(i)] = {{"spectrum", "s" + std::to_string(i + 1)}};
  s["spectra"]["s70"] = 0.5;
  s["materials"]["white"]["reflectance"] = {{"spectrum", "s0"}};
  scene_error(s, "/spectra/s63/spectrum", {"more than 64 deep (from 's0')"});
}

TEST_CASE("input limits: IES candela values that overflow are bad input, in the file and in a scene") {
  const std::string head = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n";
  // Each value finite, the flux infinite: "inf lm" in rimu-light, discarded samples or a black lamp in a scene.
  input_error([&] { parse_ies(head + "1e308 1e308\n", "huge.ies"); }, {"huge.ies:7:", "total luminous flux"});
  // A value times the multipliers overflowing.
  input_error([&] { parse_ies("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1e12 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n1e300 1\n", "m.ies"); },
              {"m.ies:7:", "overflows"});

  TempDir dir;
  dir.write("lamp.ies", head + "1e27 1e27\n");  // 2π·1e27 ≈ 6e27 lm: finite, in range
  json s = one_sphere_scene();
  s["lights"] = json::array({json::parse(R"({"type": "ies", "file": "lamp.ies", "position": [0, 3, 0],
      "spectrum": {"blackbody": 3000}})")});
  CHECK_NOTHROW(load_scene(s, "lamp.json", dir.path, test::library()));
  s["lights"][0]["candela_scale"] = 1e10;  // 6e37 lm
  const InputError e = input_error([&] { load_scene(s, "lamp.json", dir.path, test::library()); }, {"at most 1e30 lm"});
  CHECK(e.where().key == "/lights/0/candela_scale");
  s["lights"][0].erase("candela_scale");
  s["lights"][0]["luminous_power_lm"] = 1000;  // normalised: fine
  CHECK_NOTHROW(load_scene(s, "lamp.json", dir.path, test::library()));
}

TEST_CASE("input limits: a light definition's spectrum errors name its file") {
  TempDir dir;
  const json document = json::parse(R"({"type": "point", "luminous_power_lm": 800, "spectrum": {"blackbody": -5}})");
  const LightDefinition light = read_light_definition(document, "lamp.json");
  const InputError e = input_error([&] { light_shape(light, test::library(), dir.path); }, {"lamp.json: /spectrum"});
  CHECK(e.where().file == "lamp.json");

  // A light made from options with a CSV spectrum (rimu-light --csv): errors name the CSV, not "light: /spectrum".
  LightDefinition from_csv;
  from_csv.spectrum = {{"csv", dir.write("dip.csv", "wavelength_nm,power\n400,1\n500,-1\n").string()}};
  const InputError negative = input_error([&] { light_shape(from_csv, test::library(), dir.path); }, {"negative"});
  CHECK(negative.where().file == (dir.path / "dip.csv").string());
  CHECK(negative.where().key.empty());
  from_csv.spectrum = {{"csv", dir.write("infrared.csv", "wavelength_nm,power\n900,1\n1000,2\n").string()}};
  const InputError dark = input_error(
      [&] { validate_light_definition(from_csv, test::library(), dir.path, {"", 0, "--lumens"}); }, {"no power"});
  CHECK(dark.where().file == (dir.path / "infrared.csv").string());
}
