// The scene's "sensors" section (docs/scene-format.md, "Sensors"): where illuminance and luminance are measured.
// Parsing only; the measurement is render/sensors/.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/scene/json_cursor.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// A rectangle of illuminance meters: origin is a corner, u and v its unit edge directions (perpendicular),
/// size_m its edge lengths; the points are the centres of counts[0] × counts[1] equal cells (as EN 12464-1's
/// grids). Every meter faces `normal` (unit, ±u×v) and sees only the light arriving on that side.
struct IlluminanceGrid {
  std::string name;
  Vec3 origin, u, v, normal;
  float size_u_m = 0, size_v_m = 0;
  int count_u = 1, count_v = 1;
  /// "daylight_factor": true: also report DF = E / E_out in % at each point, E_out the unobstructed horizontal
  /// illuminance of the scene's CIE overcast sky (render/sensors/daylight_factor.h).
  bool daylight_factor = false;
  /// The meter point of cell (i, j), i along u and j along v.
  Vec3 point(int i, int j) const {
    return origin + u * ((float(i) + 0.5f) * size_u_m / float(count_u)) +
           v * ((float(j) + 0.5f) * size_v_m / float(count_v));
  }
};

/// One meter at a point: illuminance on a plane facing `direction` (a cosine-corrected receptor), the luminance
/// seen looking along `direction` (a luminance meter's line of sight), or the cylindrical or semi-cylindrical
/// illuminance of a small cylinder with axis `direction` (EN 12464-1, EN 13201; the semi-cylinder faces `facing`).
struct PointSensor {
  enum class Kind { illuminance, luminance, cylindrical, semi_cylindrical };
  std::string name;
  Kind kind = Kind::illuminance;
  Vec3 position, direction;  ///< direction is unit
  Vec3 facing;               ///< semi_cylindrical: unit and ⟂ direction (the given facing with its axial part removed)
};

/// The CSV/JSON name of a meter's quantity: illuminance, luminance, cylindrical_illuminance,
/// semi_cylindrical_illuminance.
const char* sensor_quantity_name(PointSensor::Kind kind);

/// The spectral weightings a measurement reports. Photopic (V(λ), lx and nt) is always measured; the others only when
/// "quantities" lists them: scotopic (V'(λ), K'_m = 1700 lm/W) and melanopic EDI/EDL (CIE S 026's s_mel(λ), as the
/// D65 illuminance or luminance of the same melanopic effect).
struct SensorQuantities {
  bool scotopic = false;
  bool melanopic = false;
};

/// Everything in "sensors". `samples` is the Monte Carlo sample count per meter point (`--sensor-samples` overrides it).
struct SensorSettings {
  int samples = 256;
  /// Independent replicates the samples are split into for the standard error (0: the default rule,
  /// render/sensors/sensor_measurement.h replicates_for; 1: one sequence, textbook standard error).
  int replicates = 0;
  SensorQuantities quantities;
  std::vector<IlluminanceGrid> grids;
  std::vector<PointSensor> points;
  bool empty() const { return grids.empty() && points.empty(); }
  size_t point_count() const;
};

/// The most sample points one scene may ask for (grids and meters together), so a typo in a spacing cannot ask for
/// billions.
inline constexpr size_t kMaxSensorPoints = size_t(1) << 20;
/// The largest per-point sample count a scene or --sensor-samples may ask for.
inline constexpr int kMaxSensorSamples = 1 << 24;

/// Reads the "sensors" object; InputError naming the key and what was expected on anything else. load_scene calls
/// it to check the section with the rest of the scene.
SensorSettings load_sensors(const JsonCursor& sensors);
/// The "sensors" of a scene document (`file` names it in errors); empty if it has none.
SensorSettings scene_sensors(const nlohmann::json& document, const std::string& file);

}  // namespace rimu
