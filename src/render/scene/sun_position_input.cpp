#include "render/scene/sun_position_input.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "transport/lights/sky/solar_position.h"

namespace rimu::scene_loading {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Vec3 unit_vector(const JsonCursor& c) {
  const Vec3 v = c.vec3();
  if (!(length(v) > 0.0f)) c.fail("a direction cannot be zero");
  return normalize(v);
}

bool leap_year(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

/// "YYYY-MM-DD", a real Gregorian date in 1800-2100 (the range NOAA states its accuracy for).
void parse_date(const JsonCursor& c, LocalDateTime& when) {
  const std::string text = c.string();
  int y = 0, m = 0, d = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2d%c", &y, &m, &d, &tail) != 3)
    c.fail("expected a date \"YYYY-MM-DD\", not \"" + text + "\"");
  constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (y < 1800 || y > 2100) c.fail("the year must be in 1800-2100 (the solar position equations' range), not " + std::to_string(y));
  if (m < 1 || m > 12 || d < 1 || d > kDays[m - 1] + (m == 2 && leap_year(y) ? 1 : 0))
    c.fail("\"" + text + "\" is not a date");
  when.year = y, when.month = m, when.day = d;
}

/// "HH:MM" or "HH:MM:SS", local clock time.
void parse_time(const JsonCursor& c, LocalDateTime& when) {
  const std::string text = c.string();
  int h = 0, m = 0;
  double s = 0;
  char tail = 0;
  const int n = std::sscanf(text.c_str(), "%2d:%2d:%lf%c", &h, &m, &s, &tail);
  if ((n != 2 && n != 3) || (n == 2 && text.size() != 5))
    c.fail("expected a local time \"HH:MM\" or \"HH:MM:SS\", not \"" + text + "\"");
  if (h < 0 || h > 23 || m < 0 || m > 59 || !(s >= 0.0 && s < 60.0)) c.fail("\"" + text + "\" is not a time of day");
  when.hours = h + m / 60.0 + s / 3600.0;
}

std::string degrees_text(double value, char positive, char negative) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g° %c", std::fabs(value), value >= 0 ? positive : negative);
  return text;
}

}  // namespace

Vec3 HorizonFrame::direction(double azimuth_deg, double elevation_deg) const {
  const double a = azimuth_deg * kDeg, h = elevation_deg * kDeg;
  const Vec3 horizontal = north * float(std::cos(a)) + east * float(std::sin(a));
  return normalize(horizontal * float(std::cos(h)) + up * float(std::sin(h)));
}

HorizonFrame horizon_frame(const JsonCursor& light) {
  HorizonFrame f;
  if (light.has("up")) f.up = unit_vector(light.at("up"));
  if (light.has("north")) {
    f.north = unit_vector(light.at("north"));
  } else if (std::fabs(dot(f.up, f.north)) > 1e-4f) {
    light.at("up").fail("with an \"up\" other than ±z, give \"north\" too (perpendicular to up)");
  }
  if (std::fabs(dot(f.up, f.north)) > 1e-4f) light.at("north").fail("north must be perpendicular to up");
  f.east = normalize(cross(f.north, f.up));
  return f;
}

SunPosition parse_sun_position(const JsonCursor& position, const HorizonFrame& frame) {
  if (!position.is_object()) position.fail("expected an object: {azimuth_deg, elevation_deg} or a place and time");
  SunPosition sun;
  if (position.has("azimuth_deg") || position.has("elevation_deg")) {
    position.only_keys({"azimuth_deg", "elevation_deg"});
    sun.azimuth_deg = position.at("azimuth_deg").number(-360.0, 360.0);
    sun.elevation_deg = position.at("elevation_deg").number(-90.0, 90.0);
    sun.description = "as given";
  } else {
    position.only_keys({"latitude_deg", "longitude_deg", "date", "time", "utc_offset_h", "pressure_mbar", "temperature_c"});
    const GeographicLocation where{position.at("latitude_deg").number(-90.0, 90.0),
                                   position.at("longitude_deg").number(-180.0, 180.0)};
    LocalDateTime when;
    parse_date(position.at("date"), when);
    parse_time(position.at("time"), when);
    when.utc_offset_h = position.at("utc_offset_h").number(-14.0, 14.0);
    const AtmosphereConditions air{position.number_or("pressure_mbar", 1010.0, 1.0, 2000.0),
                                   position.number_or("temperature_c", 10.0, -90.0, 60.0)};
    const SolarPosition p = noaa_solar_position(when, where, air);
    sun.azimuth_deg = p.azimuth_deg;
    sun.elevation_deg = p.elevation_deg;
    char offset[16];
    std::snprintf(offset, sizeof offset, "%+g", when.utc_offset_h);
    sun.description = "at " + degrees_text(where.latitude_deg, 'N', 'S') + " " +
                      degrees_text(where.longitude_deg, 'E', 'W') + ", " + position.at("date").string() + " " +
                      position.at("time").string() + " UTC" + offset;
  }
  sun.direction = frame.direction(sun.azimuth_deg, sun.elevation_deg);
  return sun;
}

std::string sun_below_horizon_warning(const std::string& light_name, const SunPosition& sun,
                                      const std::string& consequence) {
  char angle[32];
  std::snprintf(angle, sizeof angle, "%.2f°", -sun.elevation_deg);
  return light_name + ": the sun is " + angle + " below the horizon (" + sun.description + "); " + consequence;
}

}  // namespace rimu::scene_loading
