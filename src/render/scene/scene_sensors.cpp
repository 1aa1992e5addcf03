#include "render/scene/scene_sensors.h"

#include <cmath>
#include <set>

namespace rimu {
namespace {

// A unit direction from a non-zero vector.
Vec3 unit_direction(const JsonCursor& c) {
  const Vec3 d = c.vec3();
  if (!(length(d) > 0.0f)) c.fail("expected a non-zero direction [x, y, z]");
  return normalize(d);
}

// Names become parts of file names (the grid's PNG): letters, digits, '_', '-', '.'; unique in the section.
std::string sensor_name(const JsonCursor& sensor, const std::string& fallback, std::set<std::string>& taken) {
  std::string name = fallback;
  if (const auto key = sensor.find("name")) {
    name = key->string();
    const bool valid = !name.empty() && name.size() <= 64 && name.front() != '.' &&
                       name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") ==
                           std::string::npos;
    if (!valid) key->fail("expected a name of 1-64 letters, digits, '_', '-' or '.' (not starting with '.'), got '" +
                          name + "'");
  }
  if (!taken.insert(name).second)
    (sensor.has("name") ? sensor.at("name") : sensor).fail("the sensor name '" + name + "' is used twice");
  return name;
}

// "counts": [nu, nv], or "spacing": s | [su, sv] in metres (cells of at most that size: ⌈size/spacing⌉ of them).
void load_grid_counts(const JsonCursor& g, IlluminanceGrid& grid) {
  if (g.has("counts") == g.has("spacing")) g.fail("give either \"counts\": [nu, nv] or \"spacing\" (m), not both or neither");
  if (const auto counts = g.find("counts")) {
    if (!counts->is_array() || counts->size() != 2) counts->fail("expected [nu, nv], two point counts");
    grid.count_u = counts->at(0).integer(1, 4096);
    grid.count_v = counts->at(1).integer(1, 4096);
    return;
  }
  const JsonCursor spacing = g.at("spacing");
  double su = 0, sv = 0;
  if (spacing.is_array()) {
    if (spacing.size() != 2) spacing.fail("expected a spacing in metres, or [su, sv]");
    su = spacing.at(0).number(1e-4, 1e6);
    sv = spacing.at(1).number(1e-4, 1e6);
  } else {
    su = sv = spacing.number(1e-4, 1e6);
  }
  const double nu = std::ceil(grid.size_u_m / su - 1e-6), nv = std::ceil(grid.size_v_m / sv - 1e-6);
  if (nu > 4096 || nv > 4096)
    spacing.fail("gives " + std::to_string(long(nu)) + " x " + std::to_string(long(nv)) +
                 " points; at most 4096 along each edge");
  grid.count_u = std::max(1, int(nu));
  grid.count_v = std::max(1, int(nv));
}

IlluminanceGrid load_grid(const JsonCursor& g, size_t index, std::set<std::string>& names) {
  if (!g.is_object()) g.fail("expected a grid object {\"origin\", \"u\", \"v\", \"size\", \"counts\" or \"spacing\"}");
  g.only_keys({"name", "origin", "u", "v", "size", "counts", "spacing", "normal", "daylight_factor"});
  IlluminanceGrid grid;
  grid.name = sensor_name(g, "grid" + std::to_string(index), names);
  grid.origin = g.at("origin").vec3();
  grid.u = unit_direction(g.at("u"));
  grid.v = unit_direction(g.at("v"));
  if (std::fabs(dot(grid.u, grid.v)) > 1e-3f) g.at("v").fail("u and v must be perpendicular (|u·v| ≤ 1e-3 for unit u, v)");
  const JsonCursor size = g.at("size");
  if (!size.is_array() || size.size() != 2) size.fail("expected [length along u, length along v] in metres");
  grid.size_u_m = float(size.at(0).number(1e-4, 1e6));
  grid.size_v_m = float(size.at(1).number(1e-4, 1e6));
  load_grid_counts(g, grid);
  grid.daylight_factor = g.boolean_or("daylight_factor", false);
  const Vec3 plane_normal = normalize(cross(grid.u, grid.v));
  grid.normal = plane_normal;
  if (const auto normal = g.find("normal")) {
    grid.normal = unit_direction(*normal);
    if (std::fabs(std::fabs(dot(grid.normal, plane_normal)) - 1.0f) > 1e-3f)
      normal->fail("the measured side must be perpendicular to the grid: u×v or its opposite");
  }
  return grid;
}

PointSensor load_point(const JsonCursor& p, size_t index, std::set<std::string>& names) {
  if (!p.is_object()) p.fail("expected a meter object {\"type\", \"position\", \"normal\" or \"direction\"}");
  PointSensor point;
  const std::string type = p.at("type").choice({"illuminance", "luminance", "cylindrical", "semi_cylindrical"});
  point.kind = type == "illuminance"        ? PointSensor::Kind::illuminance
               : type == "luminance"        ? PointSensor::Kind::luminance
               : type == "cylindrical"      ? PointSensor::Kind::cylindrical
                                            : PointSensor::Kind::semi_cylindrical;
  point.position = p.at("position").vec3();
  if (point.kind == PointSensor::Kind::illuminance || point.kind == PointSensor::Kind::luminance) {
    const char* facing = point.kind == PointSensor::Kind::illuminance ? "normal" : "direction";
    p.only_keys({"name", "type", "position", facing});
    point.direction = unit_direction(p.at(facing));
  } else {
    // "axis" is required: scenes differ in which way is up (y-up interiors, z-up models).
    const bool semi = point.kind == PointSensor::Kind::semi_cylindrical;
    if (semi) p.only_keys({"name", "type", "position", "axis", "facing"});
    else p.only_keys({"name", "type", "position", "axis"});
    point.direction = unit_direction(p.at("axis"));
    if (semi) {
      const JsonCursor f = p.at("facing");
      const Vec3 given = unit_direction(f);
      const Vec3 across = given - point.direction * dot(given, point.direction);
      if (!(length(across) > 1e-3f)) f.fail("the semi-cylinder must face across its axis, not along it");
      point.facing = normalize(across);
    }
  }
  point.name = sensor_name(p, "meter" + std::to_string(index), names);
  return point;
}

SensorQuantities load_quantities(const JsonCursor& q) {
  if (!q.is_array()) q.fail("expected an array of \"photopic\", \"scotopic\", \"melanopic_edi\"");
  SensorQuantities quantities;
  std::set<std::string> seen;
  for (size_t i = 0; i < q.size(); ++i) {
    const std::string name = q.at(i).choice({"photopic", "scotopic", "melanopic_edi"});
    if (!seen.insert(name).second) q.at(i).fail("\"" + name + "\" is listed twice");
    if (name == "scotopic") quantities.scotopic = true;
    if (name == "melanopic_edi") quantities.melanopic = true;
  }
  return quantities;
}

}  // namespace

const char* sensor_quantity_name(PointSensor::Kind kind) {
  switch (kind) {
    case PointSensor::Kind::illuminance: return "illuminance";
    case PointSensor::Kind::luminance: return "luminance";
    case PointSensor::Kind::cylindrical: return "cylindrical_illuminance";
    case PointSensor::Kind::semi_cylindrical: return "semi_cylindrical_illuminance";
  }
  return "illuminance";
}

size_t SensorSettings::point_count() const {
  size_t n = points.size();
  for (const IlluminanceGrid& g : grids) n += size_t(g.count_u) * size_t(g.count_v);
  return n;
}

SensorSettings load_sensors(const JsonCursor& sensors) {
  if (!sensors.is_object())
    sensors.fail("expected an object {\"samples\", \"replicates\", \"quantities\", \"grids\", \"meters\"}");
  sensors.only_keys({"samples", "replicates", "quantities", "grids", "meters"});
  SensorSettings settings;
  settings.samples = sensors.integer_or("samples", settings.samples, 1, kMaxSensorSamples);
  settings.replicates = sensors.integer_or("replicates", settings.replicates, 1, 64);
  if (const auto quantities = sensors.find("quantities")) settings.quantities = load_quantities(*quantities);
  std::set<std::string> names;
  if (const auto grids = sensors.find("grids")) {
    if (!grids->is_array()) grids->fail("expected an array of grids");
    for (size_t i = 0; i < grids->size(); ++i) settings.grids.push_back(load_grid(grids->at(i), i, names));
  }
  if (const auto meters = sensors.find("meters")) {
    if (!meters->is_array()) meters->fail("expected an array of meters");
    for (size_t i = 0; i < meters->size(); ++i) settings.points.push_back(load_point(meters->at(i), i, names));
  }
  if (settings.point_count() > kMaxSensorPoints)
    sensors.fail("asks for " + std::to_string(settings.point_count()) + " meter points; at most " +
                 std::to_string(kMaxSensorPoints));
  return settings;
}

SensorSettings scene_sensors(const nlohmann::json& document, const std::string& file) {
  if (!document.is_object() || !document.contains("sensors")) return {};
  return load_sensors(JsonCursor(document, file).at("sensors"));
}

}  // namespace rimu
