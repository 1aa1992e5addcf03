#include "transport/lights/sky/solar_position.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rimu {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
double sin_deg(double x) { return std::sin(x * kDeg); }
double cos_deg(double x) { return std::cos(x * kDeg); }
double tan_deg(double x) { return std::tan(x * kDeg); }
double wrap_360(double x) { return x - 360.0 * std::floor(x / 360.0); }

/// The NOAA spreadsheet's refraction correction (degrees, to add to the geometric elevation) at standard air.
double refraction_deg(double elevation_deg) {
  if (elevation_deg > 85.0) return 0.0;
  double arcsec;
  if (elevation_deg > 5.0) {
    const double t = tan_deg(elevation_deg);
    arcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5);
  } else if (elevation_deg > -0.575) {
    const double e = elevation_deg;
    arcsec = 1735.0 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)));
  } else {
    arcsec = -20.772 / tan_deg(elevation_deg);
  }
  return arcsec / 3600.0;
}

}  // namespace

double julian_day(const LocalDateTime& when) {
  int y = when.year, m = when.month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  const int a = int(std::floor(y / 100.0));
  const int b = 2 - a + int(std::floor(a / 4.0));
  const double day_0h = std::floor(365.25 * (y + 4716)) + std::floor(30.6001 * (m + 1)) + when.day + b - 1524.5;
  return day_0h + (when.hours - when.utc_offset_h) / 24.0;
}

SolarPosition noaa_solar_position(const LocalDateTime& when, const GeographicLocation& where,
                                  const AtmosphereConditions& air) {
  SolarPosition out;
  out.julian_day = julian_day(when);
  const double t = (out.julian_day - 2451545.0) / 36525.0;  // Julian centuries from J2000.0
  const double mean_longitude = wrap_360(280.46646 + t * (36000.76983 + t * 0.0003032));
  const double mean_anomaly = 357.52911 + t * (35999.05029 - 0.0001537 * t);
  const double eccentricity = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
  const double centre = sin_deg(mean_anomaly) * (1.914602 - t * (0.004817 + 0.000014 * t)) +
                        sin_deg(2 * mean_anomaly) * (0.019993 - 0.000101 * t) + sin_deg(3 * mean_anomaly) * 0.000289;
  const double true_longitude = mean_longitude + centre;
  const double omega = 125.04 - 1934.136 * t;  // longitude of the Moon's ascending node, for nutation
  const double apparent_longitude = true_longitude - 0.00569 - 0.00478 * sin_deg(omega);
  const double mean_obliquity = 23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
  const double obliquity = mean_obliquity + 0.00256 * cos_deg(omega);
  out.right_ascension_deg = wrap_360(std::atan2(cos_deg(obliquity) * sin_deg(apparent_longitude),
                                                cos_deg(apparent_longitude)) / kDeg);
  out.declination_deg = std::asin(sin_deg(obliquity) * sin_deg(apparent_longitude)) / kDeg;

  const double y = tan_deg(obliquity / 2) * tan_deg(obliquity / 2);
  const double l2 = 2 * mean_longitude * kDeg, m1 = mean_anomaly * kDeg;
  out.equation_of_time_min = 4.0 / kDeg *
                             (y * std::sin(l2) - 2 * eccentricity * std::sin(m1) +
                              4 * eccentricity * y * std::sin(m1) * std::cos(l2) - 0.5 * y * y * std::sin(2 * l2) -
                              1.25 * eccentricity * eccentricity * std::sin(2 * m1));
  const double true_solar_min = std::fmod(when.hours * 60.0 + out.equation_of_time_min + 4.0 * where.longitude_deg -
                                              60.0 * when.utc_offset_h + 1440.0 * 4,
                                          1440.0);
  out.hour_angle_deg = true_solar_min / 4.0 < 0.0 ? true_solar_min / 4.0 + 180.0 : true_solar_min / 4.0 - 180.0;

  const double lat = where.latitude_deg, dec = out.declination_deg;
  const double cos_zenith = std::clamp(
      sin_deg(lat) * sin_deg(dec) + cos_deg(lat) * cos_deg(dec) * cos_deg(out.hour_angle_deg), -1.0, 1.0);
  const double geometric_zenith = std::acos(cos_zenith) / kDeg;
  // Azimuth from north through east: the spreadsheet's arccos form, on the side the hour angle gives.
  const double denominator = cos_deg(lat) * sin_deg(geometric_zenith);
  double azimuth = 180.0;  // the sun at the zenith or the observer at a pole: any azimuth; south by convention
  if (std::fabs(denominator) > 1e-12) {
    const double a = std::acos(std::clamp((sin_deg(lat) * cos_zenith - sin_deg(dec)) / denominator, -1.0, 1.0)) / kDeg;
    azimuth = out.hour_angle_deg > 0.0 ? wrap_360(a + 180.0) : wrap_360(540.0 - a);
  }
  out.azimuth_deg = azimuth;
  const double geometric_elevation = 90.0 - geometric_zenith;
  const double air_factor = (air.pressure_mbar / 1010.0) * (283.0 / (273.0 + air.temperature_c));
  out.elevation_deg = geometric_elevation + refraction_deg(geometric_elevation) * air_factor;
  out.zenith_deg = 90.0 - out.elevation_deg;
  return out;
}

}  // namespace rimu
