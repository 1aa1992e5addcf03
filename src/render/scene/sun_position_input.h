// The "sun_position" object of the "cie_sky" and "sun" lights, and the sky's orientation in the scene ("up",
// "north"). Internal to scene loading (docs/scene-format.md, "Daylight").
//
//   "sun_position": {"azimuth_deg": 180, "elevation_deg": 35}
//   "sun_position": {"latitude_deg": 51.48, "longitude_deg": -0.0, "date": "2026-06-21", "time": "13:00",
//                    "utc_offset_h": 1, "pressure_mbar": 1010, "temperature_c": 10}
//
// Azimuth is clockwise from north seen from above (90° east, 180° south); elevation above the horizon, apparent
// (refracted) when computed from a place and time (NOAA's equations, transport/lights/sky/solar_position.h).
// "up" (default [0, 1, 0]) is the zenith and "north" (default [0, 0, -1]) the direction of north, perpendicular to
// "up"; east is north × up (+x by default).
#pragma once

#include <string>

#include "render/scene/json_cursor.h"

namespace rimu::scene_loading {

/// The horizon frame of a daylight light: unit up and north, east = north × up.
struct HorizonFrame {
  Vec3 up{0, 1, 0}, north{0, 0, -1}, east{1, 0, 0};
  /// The world direction towards azimuth `azimuth_deg` (from north through east) and elevation `elevation_deg`.
  Vec3 direction(double azimuth_deg, double elevation_deg) const;
};

/// "up" and "north" of `light` (defaults above); errors name the key when zero or not perpendicular.
HorizonFrame horizon_frame(const JsonCursor& light);

/// Where the sun is.
struct SunPosition {
  double azimuth_deg = 0, elevation_deg = 0;
  Vec3 direction;            ///< world, unit, from the scene towards the sun
  std::string description;   ///< "at 39.74° N 105.18° W, 2003-10-17 12:30:30 UTC-7" or "as given"
};

/// Reads a "sun_position" object (either form above; a mix is an error naming the keys).
SunPosition parse_sun_position(const JsonCursor& position, const HorizonFrame& frame);

/// The load-time warning for a sun below the horizon, naming the light, the elevation, where and when, and what
/// the light does about it (`consequence`).
std::string sun_below_horizon_warning(const std::string& light_name, const SunPosition& sun,
                                      const std::string& consequence);

}  // namespace rimu::scene_loading
