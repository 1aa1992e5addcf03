#include "render/scene/camera_keyframes.h"

#include <array>
#include <cmath>
#include <vector>

#include "render/scene/json_cursor.h"

namespace rimu {
namespace {

using Point = std::array<double, 3>;

// Doubles, not the loader's floats: a key given in the file comes back exactly at its own frame.
Point point(const JsonCursor& c) {
  if (!c.is_array() || c.size() != 3) c.fail("expected an array of 3 numbers, found " + json_preview(c.value()));
  return {c.at(size_t(0)).number(), c.at(size_t(1)).number(), c.at(size_t(2)).number()};
}

struct Key {
  int frame = 0;
  Point from{}, to{}, up{};
  double fov_deg = 40.0;
};

Point mix(const Point& a, const Point& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

}  // namespace

void apply_camera_keyframes(nlohmann::json& document, int frame, const std::string& file) {
  if (!document.is_object() || !document.contains("camera") || !document["camera"].is_object() ||
      !document["camera"].contains("keyframes"))
    return;
  Key fallback;
  std::vector<Key> keys;
  {
    const JsonCursor camera(document["camera"], file, "/camera");
    for (const char* key : {"from", "to"})
      if (camera.has(key))
        camera.at(key).fail(std::string("a camera with \"keyframes\" takes '") + key + "' from its keys, not here");
    fallback.up = camera.has("up") ? point(camera.at("up")) : Point{0, 1, 0};
    fallback.fov_deg = camera.number_or("vertical_fov_deg", 40.0, 1e-3, 179.0);
    const std::string type = camera.has("type") && camera.at("type").is_string() ? camera.at("type").string() : "";
    const bool has_fov = type != "orthographic" && type != "spherical";
    const JsonCursor list = camera.at("keyframes");
    if (!list.is_array() || list.size() == 0)
      list.fail("expected a non-empty array of keys {\"frame\": N, \"from\": [x, y, z], \"to\": [x, y, z]}");
    for (size_t i = 0; i < list.size(); ++i) {
      const JsonCursor k = list.at(i);
      k.only_keys({"frame", "from", "to", "up", "vertical_fov_deg"});
      Key key;
      key.frame = k.at("frame").integer(-1000000000, 1000000000);
      if (!keys.empty() && key.frame <= keys.back().frame)
        k.at("frame").fail("keyframes must be in increasing frame order: frame " + std::to_string(key.frame) +
                           " follows frame " + std::to_string(keys.back().frame));
      key.from = point(k.at("from"));
      key.to = point(k.at("to"));
      key.up = k.has("up") ? point(k.at("up")) : fallback.up;
      if (!has_fov && k.has("vertical_fov_deg"))
        k.at("vertical_fov_deg").fail("a " + type + " camera has no field of view to key");
      key.fov_deg = k.number_or("vertical_fov_deg", fallback.fov_deg, 1e-3, 179.0);
      keys.push_back(key);
    }
  }
  // The keys around `frame`: held before the first and after the last.
  size_t next = 0;
  while (next < keys.size() && keys[next].frame < frame) ++next;
  Key at = keys[std::min(next, keys.size() - 1)];
  if (next > 0 && next < keys.size() && keys[next].frame != frame) {
    const Key& a = keys[next - 1];
    const Key& b = keys[next];
    const double t = double(frame - a.frame) / double(b.frame - a.frame);
    at = {frame, mix(a.from, b.from, t), mix(a.to, b.to, t), mix(a.up, b.up, t),
          a.fov_deg + t * (b.fov_deg - a.fov_deg)};
  }
  const Point view{at.to[0] - at.from[0], at.to[1] - at.from[1], at.to[2] - at.from[2]};
  const Point side{at.up[1] * view[2] - at.up[2] * view[1], at.up[2] * view[0] - at.up[0] * view[2],
                   at.up[0] * view[1] - at.up[1] * view[0]};
  const JsonCursor list(document["camera"]["keyframes"], file, "/camera/keyframes");
  auto norm = [](const Point& p) { return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]); };
  if (norm(view) == 0.0)
    list.fail("at frame " + std::to_string(frame) + " the camera path's 'to' equals its 'from': no viewing direction");
  if (norm(side) == 0.0)
    list.fail("at frame " + std::to_string(frame) + " the camera path's 'up' is parallel to the viewing direction");

  nlohmann::json& camera = document["camera"];
  camera.erase("keyframes");
  camera["from"] = at.from;
  camera["to"] = at.to;
  camera["up"] = at.up;
  // Only the perspective cameras have a field of view (the others refuse the key, and their keys may not give it).
  const std::string type = camera.contains("type") && camera["type"].is_string() ? camera["type"].get<std::string>() : "";
  if (type != "orthographic" && type != "spherical") camera["vertical_fov_deg"] = at.fov_deg;
}

}  // namespace rimu
