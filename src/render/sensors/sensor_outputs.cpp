#include "render/sensors/sensor_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "spectral/io/output_file.h"

namespace rimu {
namespace {

// Enough digits to keep a reading's standard error meaningful (a 0.1 % error on 100 000 lx needs 7).
std::string number_text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.7g", x);
  return buffer;
}

nlohmann::json vec3_json(Vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); }

// A number JSON can hold (a reading is finite by construction; this keeps a 0/0 statistic out of the file).
nlohmann::json finite_json(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

// The extra quantities (SensorSettings::quantities): index 0 scotopic, 1 melanopic; their JSON keys.
constexpr const char* kExtraKeys[2] = {"scotopic", "melanopic_edi"};

// The CSV quantity of an extra weighting of a meter's base quantity: scotopic_<base>; melanopic_edi (illuminance),
// melanopic_edl (luminance), melanopic_edi_<cylinder kind>.
std::string extra_quantity(int extra, const std::string& base) {
  if (extra == 0) return "scotopic_" + base;
  if (base == "illuminance") return "melanopic_edi";
  if (base == "luminance") return "melanopic_edl";
  return "melanopic_edi_" + base.substr(0, base.size() - std::string("_illuminance").size());
}

const std::vector<MeterReading>& grid_extra(const GridReadings& r, int extra) {
  return extra == 0 ? r.scotopic_points : r.melanopic_points;
}
const std::vector<MeterReading>& meter_extra(const SensorReadings& r, int extra) {
  return extra == 0 ? r.meters_scotopic : r.meters_melanopic;
}

// Emin, Eavg, Emax and U0 of an extra quantity's grid readings.
nlohmann::json extra_statistics(const std::vector<MeterReading>& points) {
  double lo = points.front().value, hi = lo, sum = 0.0;
  for (const MeterReading& m : points) {
    lo = std::min(lo, m.value);
    hi = std::max(hi, m.value);
    sum += m.value;
  }
  const double avg = sum / double(points.size());
  return {{"e_min", lo}, {"e_avg", avg}, {"e_max", hi}, {"u0", finite_json(avg > 0.0 ? lo / avg : 0.0)}};
}

}  // namespace

SensorOutputPaths sensor_output_paths(const std::filesystem::path& base) {
  return {std::filesystem::path(base.string() + ".csv"), std::filesystem::path(base.string() + ".json")};
}

std::filesystem::path default_sensor_output_base(const std::filesystem::path& exr) {
  std::filesystem::path base = exr;
  if (lower_case_extension(base) == "exr") base.replace_extension();
  return std::filesystem::path(base.string() + ".sensors");
}

std::string sensor_csv(const SensorSettings& sensors, const SensorReadings& readings) {
  std::ostringstream csv;
  csv << "sensor,quantity,i,j,x,y,z,dx,dy,dz,value,standard_error,unit,samples\n";
  // quantity and unit: illuminance lx, luminance nt, daylight_factor % (a grid's second set of rows).
  auto row = [&](const std::string& name, const char* quantity, const char* unit, const std::string& i,
                 const std::string& j, Vec3 p, Vec3 d, const MeterReading& r) {
    csv << name << ',' << quantity << ',' << i << ',' << j;
    for (float c : {p.x, p.y, p.z, d.x, d.y, d.z}) csv << ',' << number_text(c);
    csv << ',' << number_text(r.value) << ',' << number_text(r.standard_error) << ',' << unit << ',' << r.samples
        << '\n';
  };
  for (size_t g = 0; g < sensors.grids.size() && g < readings.grids.size(); ++g) {
    const IlluminanceGrid& grid = sensors.grids[g];
    for (int j = 0; j < grid.count_v; ++j)
      for (int i = 0; i < grid.count_u; ++i)
        row(grid.name, "illuminance", "lx", std::to_string(i), std::to_string(j), grid.point(i, j), grid.normal,
            readings.grids[g].points[size_t(j * grid.count_u + i)]);
    if (const auto& df = readings.grids[g].daylight_factor)
      for (int j = 0; j < grid.count_v; ++j)
        for (int i = 0; i < grid.count_u; ++i)
          row(grid.name, "daylight_factor", "%", std::to_string(i), std::to_string(j), grid.point(i, j), grid.normal,
              df->points_percent[size_t(j * grid.count_u + i)]);
    for (int extra = 0; extra < 2; ++extra) {
      const std::vector<MeterReading>& points = grid_extra(readings.grids[g], extra);
      if (points.empty()) continue;
      const std::string quantity = extra_quantity(extra, "illuminance");
      for (int j = 0; j < grid.count_v; ++j)
        for (int i = 0; i < grid.count_u; ++i)
          row(grid.name, quantity.c_str(), "lx", std::to_string(i), std::to_string(j), grid.point(i, j), grid.normal,
              points[size_t(j * grid.count_u + i)]);
    }
  }
  for (size_t k = 0; k < sensors.points.size() && k < readings.meters.size(); ++k) {
    const PointSensor& p = sensors.points[k];
    const std::string base = sensor_quantity_name(p.kind);
    const char* unit = p.kind == PointSensor::Kind::luminance ? "nt" : "lx";
    row(p.name, base.c_str(), unit, "", "", p.position, p.direction, readings.meters[k]);
    for (int extra = 0; extra < 2; ++extra)
      if (k < meter_extra(readings, extra).size())
        row(p.name, extra_quantity(extra, base).c_str(), unit, "", "", p.position, p.direction,
            meter_extra(readings, extra)[k]);
  }
  return csv.str();
}

nlohmann::json sensor_json(const SensorSettings& sensors, const SensorReadings& readings, int samples) {
  nlohmann::json doc;
  doc["samples_per_point"] = samples;
  doc["discarded_samples"] = readings.discarded_samples;
  doc["seconds"] = readings.seconds;
  doc["grids"] = nlohmann::json::array();
  for (size_t g = 0; g < sensors.grids.size() && g < readings.grids.size(); ++g) {
    const IlluminanceGrid& grid = sensors.grids[g];
    const GridReadings& r = readings.grids[g];
    nlohmann::json points = nlohmann::json::array();
    for (int j = 0; j < grid.count_v; ++j)
      for (int i = 0; i < grid.count_u; ++i) {
        const size_t k = size_t(j * grid.count_u + i);
        const MeterReading& m = r.points[k];
        points.push_back({{"i", i}, {"j", j}, {"position", vec3_json(grid.point(i, j))}, {"value", m.value},
                          {"standard_error", m.standard_error}});
        if (r.daylight_factor) {
          points.back()["daylight_factor_percent"] = r.daylight_factor->points_percent[k].value;
          points.back()["daylight_factor_standard_error_percent"] = r.daylight_factor->points_percent[k].standard_error;
        }
        for (int extra = 0; extra < 2; ++extra)
          if (!grid_extra(r, extra).empty())
            points.back()[kExtraKeys[extra]] = {{"value", grid_extra(r, extra)[k].value},
                                                {"standard_error", grid_extra(r, extra)[k].standard_error}};
      }
    doc["grids"].push_back({{"name", grid.name},
                            {"quantity", "illuminance"},
                            {"unit", "lx"},
                            {"origin", vec3_json(grid.origin)},
                            {"u", vec3_json(grid.u)},
                            {"v", vec3_json(grid.v)},
                            {"normal", vec3_json(grid.normal)},
                            {"size_m", {grid.size_u_m, grid.size_v_m}},
                            {"counts", {grid.count_u, grid.count_v}},
                            {"e_min", r.e_min_lx},
                            {"e_avg", r.e_avg_lx},
                            {"e_max", r.e_max_lx},
                            {"u0", finite_json(r.u0)},
                            {"points", points}});
    if (const auto& df = r.daylight_factor)
      doc["grids"].back()["daylight_factor"] = {{"sky", "CIE standard overcast sky (type 1)"},
                                                {"outdoor_illuminance_lx", df->outdoor_illuminance_lx},
                                                {"df_min_percent", df->df_min_percent},
                                                {"df_avg_percent", df->df_avg_percent},
                                                {"df_max_percent", df->df_max_percent}};
    for (int extra = 0; extra < 2; ++extra)
      if (!grid_extra(r, extra).empty()) {
        nlohmann::json summary = extra_statistics(grid_extra(r, extra));
        summary["quantity"] = extra_quantity(extra, "illuminance");
        summary["unit"] = "lx";
        doc["grids"].back()[kExtraKeys[extra]] = summary;
      }
  }
  doc["meters"] = nlohmann::json::array();
  for (size_t k = 0; k < sensors.points.size() && k < readings.meters.size(); ++k) {
    const PointSensor& p = sensors.points[k];
    const std::string base = sensor_quantity_name(p.kind);
    const char* unit = p.kind == PointSensor::Kind::luminance ? "nt" : "lx";
    const char* direction_key = p.kind == PointSensor::Kind::illuminance ? "normal"
                                : p.kind == PointSensor::Kind::luminance ? "direction"
                                                                         : "axis";
    doc["meters"].push_back({{"name", p.name},
                             {"quantity", base},
                             {"unit", unit},
                             {"position", vec3_json(p.position)},
                             {direction_key, vec3_json(p.direction)},
                             {"value", readings.meters[k].value},
                             {"standard_error", readings.meters[k].standard_error}});
    if (p.kind == PointSensor::Kind::semi_cylindrical) doc["meters"].back()["facing"] = vec3_json(p.facing);
    for (int extra = 0; extra < 2; ++extra)
      if (k < meter_extra(readings, extra).size())
        doc["meters"].back()[kExtraKeys[extra]] = {{"quantity", extra_quantity(extra, base)},
                                                   {"unit", unit},
                                                   {"value", meter_extra(readings, extra)[k].value},
                                                   {"standard_error", meter_extra(readings, extra)[k].standard_error}};
  }
  return doc;
}

void write_sensor_outputs(const SensorOutputPaths& paths, const SensorSettings& sensors, const SensorReadings& readings,
                          int samples) {
  write_text_file(paths.csv, sensor_csv(sensors, readings));
  write_text_file(paths.json, sensor_json(sensors, readings, samples).dump(2) + "\n");
}

}  // namespace rimu
