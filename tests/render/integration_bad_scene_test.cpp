// Bad scenes: every user error is an InputError raised at load time that names where it is — the JSON key path
// (or the line, for malformed JSON) — and the scene never reaches the renderer. Degenerate triangles are not an
// error: they are dropped, counted, and the render stays free of NaN. (The same scenes through the `rimu` CLI,
// with exit code 1 and the message, are CTest entries in tests/CMakeLists.txt using tests/cli/bad_*.json.)
#include <doctest/doctest.h>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "integration_support.h"
#include "render/scene/json_cursor.h"

using namespace rimu;
using namespace rimu::test;
namespace fs = std::filesystem;

namespace integration_bad_scene_test {

// A valid one-sphere scene to break one key at a time.
nlohmann::json valid_scene() {
  return nlohmann::json::parse(R"({
    "camera": {"from": [0, 0, -3], "to": [0, 0, 0]},
    "film": {"resolution": [8, 8], "filter": {"type": "box"}},
    "materials": {"white": {"type": "diffuse", "reflectance": 0.8}},
    "shapes": [
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"},
      {"type": "quad", "material": "white", "vertices": [[-2, -1, -2], [-2, -1, 2], [2, -1, 2], [2, -1, -2]]}
    ],
    "lights": [{"type": "environment", "radiance": 1}]
  })");
}

// The InputError that loading `scene` throws (fails the test if it loads).
InputError load_error(const nlohmann::json& scene) {
  try {
    scene_from_json(scene, "bad.json");
  } catch (const InputError& e) {
    return e;
  }
  FAIL("the scene loaded without error");
  return InputError({}, "");
}

void check_error(const nlohmann::json& scene, const std::string& key, const std::string& text) {
  const InputError e = load_error(scene);
  CAPTURE(e.what());
  CHECK(e.where().file == "bad.json");
  CHECK(e.where().key == key);
  CHECK(std::string(e.what()).find(text) != std::string::npos);
  // what() leads with the location, so a user sees file and key path first.
  CHECK(std::string(e.what()).rfind("bad.json: " + key + ": ", 0) == 0);
}

TEST_CASE("bad scene: malformed JSON names the file and the line") {
  const fs::path path = fs::temp_directory_path() / ("rimu-bad-json-" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << "{\n  \"camera\": {\"from\": [0, 0, -3], \"to\": [0, 0, 0]},\n  \"shapes\": [\n    {\"type\": \"sphere\",, }\n  ]\n}\n";
  try {
    load_scene(path, library());
    FAIL("malformed JSON loaded");
  } catch (const InputError& e) {
    CAPTURE(e.what());
    CHECK(e.where().file == path.string());
    CHECK(e.where().line == 4);  // the doubled comma
    CHECK(std::string(e.what()).find("malformed JSON") != std::string::npos);
  }
  fs::remove(path);
}

TEST_CASE("bad scene: a missing scene file is an InputError naming it") {
  const fs::path path = fs::temp_directory_path() / "rimu-no-such-scene.json";
  CHECK_THROWS_AS(load_scene(path, library()), InputError);
}

TEST_CASE("bad scene: unknown material, negative radius, unknown key, missing mesh file") {
  nlohmann::json s = valid_scene();
  s["shapes"][0]["material"] = "chrome";
  check_error(s, "/shapes/0/material", "unknown material 'chrome'; defined: white");

  s = valid_scene();
  s["shapes"][0]["radius"] = -1.0;
  check_error(s, "/shapes/0/radius", "");

  s = valid_scene();
  s["shapes"][0]["radious"] = 1.0;  // a typo must not be ignored
  check_error(s, "/shapes/0/radious", "unknown key 'radious'");

  s = valid_scene();
  s["materials"]["white"]["albedo"] = 0.5;
  check_error(s, "/materials/white/albedo", "unknown key 'albedo'");

  s = valid_scene();
  s["shapes"][1] = {{"type", "mesh"}, {"file", "no/such/mesh.obj"}, {"material", "white"}};
  const InputError e = load_error(s);
  CAPTURE(e.what());
  CHECK(e.where().key == "/shapes/1/file");
  CHECK(std::string(e.what()).find("mesh.obj") != std::string::npos);
}

TEST_CASE("bad scene: a film crop_window must be fractions in order, and not beside a crop in pixels") {
  nlohmann::json s = valid_scene();
  s["film"]["crop_window"] = {0.5, 0.0, 0.25, 1.0};
  check_error(s, "/film/crop_window", "expected x0 < x1 and y0 < y1");
  s["film"]["crop_window"] = {0.0, 0.0, 1.5, 1.0};
  check_error(s, "/film/crop_window/2", "");
  s["film"]["crop_window"] = {0.0, 0.0, 0.5};
  check_error(s, "/film/crop_window", "expected [x0, y0, x1, y1]");
  s["film"]["crop_window"] = {0.0, 0.0, 0.5, 0.5};
  s["film"]["crop"] = {0, 0, 2, 2};
  check_error(s, "/film/crop_window", "not both");
  s["film"].erase("crop");
  CHECK(scene_from_json(s, "good.json")->settings.crop_window == CropWindow{0.0, 0.0, 0.5, 0.5});
}

TEST_CASE("bad scene: non-finite and huge numbers in a transform") {
  // JSON has no NaN or Infinity literals. nlohmann refuses an overflowing literal such as 1e400 with an
  // out_of_range exception (406, "number overflow") that carries no position; the loader turns it into an
  // InputError with the line of the literal.
  CHECK_THROWS_AS(nlohmann::json::parse("[1e400]"), nlohmann::json::out_of_range);
  try {
    parse_json_text("{\n  \"shapes\": [\n    {\"transform\": [{\"translate\": [0, 1e400, 0]}]}\n  ]\n}\n", "overflow.json");
    FAIL("1e400 parsed");
  } catch (const InputError& e) {
    CAPTURE(e.what());
    CHECK(e.where().file == "overflow.json");
    CHECK(e.where().line == 3);
    CHECK(std::string(e.what()).find("1e400") != std::string::npos);
  }

  // A document built in code can hold ±inf and NaN (a script's output, or an API user): rejected at the key.
  const double inf = std::numeric_limits<double>::infinity();
  nlohmann::json s = valid_scene();
  s["shapes"][1]["transform"] = {{{"translate", {0.0, inf, 0.0}}}};
  check_error(s, "/shapes/1/transform/0/translate/1", "finite");

  s = valid_scene();
  s["shapes"][1]["transform"] = {{{"rotate", {{"angle_deg", std::nan("")}, {"axis", {0, 1, 0}}}}}};
  check_error(s, "/shapes/1/transform/0/rotate/angle_deg", "finite");

  // A NaN written as a string (what a script dumping NaN might produce) is a type error at the same place.
  s = valid_scene();
  s["shapes"][1]["transform"] = nlohmann::json::parse(R"([{"translate": [0, "NaN", 0]}])");
  check_error(s, "/shapes/1/transform/0/translate/1", "expected a number");

  // Each step finite (1e25 is accepted) but their product 1e50 overflows float: the combined transform is rejected.
  s = valid_scene();
  s["shapes"][1]["transform"] = nlohmann::json::parse(R"([{"scale": 1e25}, {"scale": 1e25}])");
  check_error(s, "/shapes/1/transform", "not finite");

  // A sphere centre at infinity.
  s = valid_scene();
  s["shapes"][0]["center"] = {0.0, 0.0, -inf};
  check_error(s, "/shapes/0/center/2", "finite");
}

TEST_CASE("bad scene: singular transforms") {
  nlohmann::json s = valid_scene();
  s["shapes"][1]["transform"] = nlohmann::json::parse(R"([{"scale": [1, 0, 1]}])");
  check_error(s, "/shapes/1/transform/0/scale", "collapses");

  // A 3×4 matrix whose linear part has rank 2 (third row = first + second).
  s = valid_scene();
  s["shapes"][1]["transform"] = nlohmann::json::parse(R"([{"matrix": [1, 0, 0, 0,  0, 1, 0, 0,  1, 1, 0, 0]}])");
  check_error(s, "/shapes/1/transform/0/matrix", "singular");

  // Two regular steps whose product is numerically singular: 1e-25 scales twice give a determinant of 1e-150 → 0
  // in float.
  s = valid_scene();
  s["shapes"][1]["transform"] = nlohmann::json::parse(R"([{"scale": 1e-25}, {"scale": 1e-25}])");
  check_error(s, "/shapes/1/transform", "singular");
}

TEST_CASE("bad scene: degenerate triangles are removed and counted, and the render has no NaN") {
  nlohmann::json s = valid_scene();
  // Four triangles: two make a 4 m square floor; one repeats a vertex (zero area); one is collinear.
  s["shapes"][1] = nlohmann::json::parse(R"({
    "type": "triangles", "material": "white",
    "positions": [[-2, -1, -2], [-2, -1, 2], [2, -1, 2], [2, -1, -2], [0, -1, 0], [1, -1, 1]],
    "indices": [0, 1, 2,  0, 2, 3,  1, 1, 2,  0, 4, 5]
  })");
  const auto scene = scene_from_json(s, "degenerate.json");
  CHECK(scene->degenerate_triangles_removed == 2);
  const RenderedFilm rendered = render_xyz(*scene, 4, 1);
  CHECK(rendered.film->sample_counts().discarded() == 0);
  CHECK(rendered.film->sample_counts().accepted == uint64_t(8 * 8 * 4));
  for (double y : luminance_values(*rendered.film)) CHECK(std::isfinite(y));

  // A mesh of nothing but degenerate triangles is dropped whole, not an error.
  s["shapes"][1]["indices"] = {1, 1, 2};
  CHECK(scene_from_json(s, "degenerate.json")->degenerate_triangles_removed == 1);
}

}  // namespace integration_bad_scene_test
