// What a sensor measurement hands a lighting designer: a CSV table (one row per meter point) and a JSON document
// (the same with each grid's Emin, Eavg, Emax and U0), written atomically.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "render/scene/scene_sensors.h"
#include "render/sensors/sensor_measurement.h"

namespace rimu {

/// The files of a measurement with base name `base`: base.csv and base.json.
struct SensorOutputPaths {
  std::filesystem::path csv, json;
};
SensorOutputPaths sensor_output_paths(const std::filesystem::path& base);
/// The default base beside the EXR: "render.exr" → "render.sensors" (render.sensors.csv, render.sensors.json).
std::filesystem::path default_sensor_output_base(const std::filesystem::path& exr);

/// One row per point: sensor, quantity (illuminance | luminance | cylindrical_illuminance |
/// semi_cylindrical_illuminance | daylight_factor | the extra quantities' names), i, j (grid cell; empty for
/// meters), x, y, z, the direction (a cylinder's axis), value, standard_error, unit (lx | nt | %), samples. A
/// daylight-factor grid has its illuminance rows, then one daylight_factor row per point; a grid's scotopic and
/// melanopic rows follow (scotopic_illuminance, melanopic_edi), and each meter's follow its own row
/// (scotopic_<quantity>; melanopic_edi, melanopic_edl, melanopic_edi_<cylinder kind>).
std::string sensor_csv(const SensorSettings& sensors, const SensorReadings& readings);
/// {"samples", "grids": [{name, origin, u, v, normal, size_m, counts, unit, e_min, e_avg, e_max, u0,
/// points: [{i, j, position, value, standard_error}]}], "meters": [...]}; a daylight-factor grid adds
/// "daylight_factor": {sky, outdoor_illuminance_lx, df_min_percent, df_avg_percent, df_max_percent} and each point
/// daylight_factor_percent and daylight_factor_standard_error_percent. The extra quantities add "scotopic" and
/// "melanopic_edi" objects: to a grid {quantity, unit, e_min, e_avg, e_max, u0}, to each point {value,
/// standard_error}, to a meter {quantity, unit, value, standard_error}. Cylindrical meters give "axis" (and
/// "facing") instead of "normal".
nlohmann::json sensor_json(const SensorSettings& sensors, const SensorReadings& readings, int samples);

/// Writes both files through write_atomically (spectral/io/output_file.h): each appears complete or not at all.
void write_sensor_outputs(const SensorOutputPaths& paths, const SensorSettings& sensors, const SensorReadings& readings,
                          int samples);

}  // namespace rimu
