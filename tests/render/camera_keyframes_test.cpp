// A camera path keyed by frame (render/scene/camera_keyframes.h): linear between keys, exact at a key, held outside the
// keys, and malformed paths are InputErrors naming the key.
#include <doctest/doctest.h>

#include "render/scene/camera_keyframes.h"
#include "spectral/error.h"

using namespace rimu;
using nlohmann::json;

namespace {

// A dolly from z = 10 to z = 0 over frames 1-11 while the view turns from -z to +x and the lens zooms 40° → 20°.
json dolly() {
  return json::parse(R"({"camera": {"type": "pinhole", "up": [0, 1, 0], "keyframes": [
      {"frame": 1, "from": [0, 1, 10], "to": [0, 1, 0], "vertical_fov_deg": 40},
      {"frame": 11, "from": [0, 1, 0], "to": [5, 1, 0], "up": [0, 0, 1], "vertical_fov_deg": 20}]}})");
}

json camera_at(int frame) {
  json document = dolly();
  apply_camera_keyframes(document, frame, "dolly.json");
  return document["camera"];
}

}  // namespace

TEST_CASE("camera keyframes: a key's own frame gives the key exactly, the keys' camera replaces the keyframes") {
  const json c = camera_at(11);
  CHECK(c["from"] == json::array({0.0, 1.0, 0.0}));
  CHECK(c["to"] == json::array({5.0, 1.0, 0.0}));
  CHECK(c["up"] == json::array({0.0, 0.0, 1.0}));
  CHECK(c["vertical_fov_deg"] == 20.0);
  CHECK_FALSE(c.contains("keyframes"));
  CHECK(c["type"] == "pinhole");  // the rest of the camera is kept
  CHECK(camera_at(1)["up"] == json::array({0.0, 1.0, 0.0}));  // a key without "up" takes the camera's
}

TEST_CASE("camera keyframes: linear in from, to, up and field of view between two keys") {
  // Frame 6 is half way (t = 5/10); frame 3 is t = 2/10 = 0.2.
  const json half = camera_at(6);
  CHECK(half["from"][2].get<double>() == doctest::Approx(5.0).epsilon(1e-15));
  CHECK(half["to"][0].get<double>() == doctest::Approx(2.5).epsilon(1e-15));
  CHECK(half["up"][1].get<double>() == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(half["up"][2].get<double>() == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(half["vertical_fov_deg"].get<double>() == doctest::Approx(30.0).epsilon(1e-15));
  const json early = camera_at(3);
  CHECK(early["from"][2].get<double>() == doctest::Approx(8.0).epsilon(1e-15));
  CHECK(early["vertical_fov_deg"].get<double>() == doctest::Approx(36.0).epsilon(1e-15));
}

TEST_CASE("camera keyframes: held at the first key before it and at the last key after it") {
  CHECK(camera_at(-5)["from"] == json::array({0.0, 1.0, 10.0}));
  CHECK(camera_at(500)["to"] == json::array({5.0, 1.0, 0.0}));
}

TEST_CASE("camera keyframes: a camera without keyframes is left alone") {
  json document = json::parse(R"({"camera": {"from": [0, 0, 3], "to": [0, 0, 0]}})");
  const json before = document;
  apply_camera_keyframes(document, 7, "plain.json");
  CHECK(document == before);
}

TEST_CASE("camera keyframes: malformed paths are errors naming the key") {
  auto error_of = [](const char* text, int frame) {
    json document = json::parse(text);
    try {
      apply_camera_keyframes(document, frame, "path.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string order = error_of(R"({"camera": {"keyframes": [{"frame": 5, "from": [0, 0, 1], "to": [0, 0, 0]},
                                          {"frame": 5, "from": [0, 0, 2], "to": [0, 0, 0]}]}})", 5);
  CHECK(order.find("/camera/keyframes/1/frame") != std::string::npos);
  CHECK(order.find("increasing frame order") != std::string::npos);
  const std::string both = error_of(R"({"camera": {"from": [0, 0, 1], "keyframes": [
                                          {"frame": 1, "from": [0, 0, 1], "to": [0, 0, 0]}]}})", 1);
  CHECK(both.find("/camera/from") != std::string::npos);
  const std::string missing = error_of(R"({"camera": {"keyframes": [{"frame": 1, "from": [0, 0, 1]}]}})", 1);
  CHECK(missing.find("/camera/keyframes/0") != std::string::npos);
  CHECK(missing.find("to") != std::string::npos);
  const std::string empty = error_of(R"({"camera": {"keyframes": []}})", 1);
  CHECK(empty.find("non-empty array") != std::string::npos);
  // The eye and the target swap places between frames 0 and 2: at frame 1 they meet.
  const std::string meet = error_of(R"({"camera": {"keyframes": [{"frame": 0, "from": [0, 0, 0], "to": [2, 0, 0]},
                                         {"frame": 2, "from": [2, 0, 0], "to": [0, 0, 0]}]}})", 1);
  CHECK(meet.find("at frame 1") != std::string::npos);
  CHECK(meet.find("no viewing direction") != std::string::npos);
  CHECK(error_of(R"({"camera": {"keyframes": [{"frame": 0, "from": [0, 0, 0], "to": [2, 0, 0]},
                                   {"frame": 2, "from": [2, 0, 0], "to": [0, 0, 0]}]}})", 0) == "no error");
  // A spherical or orthographic camera has no field of view: a key giving one is an error, and none is written.
  const std::string spherical = error_of(R"({"camera": {"type": "spherical", "keyframes": [
                                              {"frame": 1, "from": [0, 0, 1], "to": [0, 0, 0], "vertical_fov_deg": 30}]}})", 1);
  CHECK(spherical.find("/camera/keyframes/0/vertical_fov_deg") != std::string::npos);
  CHECK(spherical.find("no field of view") != std::string::npos);
  json panorama = json::parse(R"({"camera": {"type": "spherical", "keyframes": [
                                    {"frame": 1, "from": [0, 0, 1], "to": [0, 0, 0]}]}})");
  apply_camera_keyframes(panorama, 1, "path.json");
  CHECK_FALSE(panorama["camera"].contains("vertical_fov_deg"));
}
