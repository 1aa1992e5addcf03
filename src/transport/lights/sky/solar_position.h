// Where the sun is, seen from a place on Earth at a date and time: the NOAA solar calculator's equations.
//
// Algorithm: NOAA Global Monitoring Laboratory's Solar Calculator (the "NOAA_Solar_Calculations_day.xls"
// spreadsheet, gml.noaa.gov/grad/solcalc/calcdetails.html), which follows Meeus, "Astronomical Algorithms" (1991),
// ch. 24-28 in its low-precision form: the Julian century from the Julian day, the sun's geometric mean longitude
// and anomaly, the equation of the centre (three terms), the apparent longitude (nutation and aberration in one
// term), the corrected obliquity, declination and right ascension, the equation of time, the hour angle, then
// zenith and azimuth, and the atmospheric refraction approximation the spreadsheet uses (Bennett's form above
// 5°, a polynomial down to −0.575°). Time is treated as UT (ΔT ≈ 1 min is neglected) and no topocentric parallax
// (≤ 0.0024°) is applied.
//
// Accuracy as NOAA states it: "theoretically accurate to within a minute of arc" (0.0167°) for dates 1800-2100
// and latitudes within ±72°; the refraction makes the elevation uncertain near the horizon. Tested against the
// NREL SPA paper's example (Reda & Andreas, "Solar position algorithm for solar radiation applications", NREL/TP-
// 560-34302, 2008, Table A5.1): 17 October 2003 12:30:30 local (UTC−7), Golden CO (39.742476° N, 105.1786° W),
// 820 mbar, 11 °C: topocentric zenith 50.11162°, azimuth 194.34024° — this implementation is within 0.01° of both.
//
// Refraction is scaled for the air's pressure and temperature by (P/1010 mbar)·(283 K/(273 + T °C)) (Meeus ch. 16;
// the NOAA spreadsheet has no such inputs, i.e. P = 1010 mbar and T = 10 °C, the default here).
#pragma once

namespace rimu {

/// A local civil date and time, and its offset from UTC (hours, east positive: Central European Time is +1,
/// Mountain Standard Time −7).
struct LocalDateTime {
  int year = 2000, month = 1, day = 1;  ///< Gregorian calendar
  double hours = 12.0;                  ///< local time of day in hours, [0, 24)
  double utc_offset_h = 0.0;
};

/// Latitude (north positive) and longitude (east positive), degrees.
struct GeographicLocation {
  double latitude_deg = 0.0, longitude_deg = 0.0;
};

/// The air at the observer, for refraction. The defaults give the NOAA spreadsheet's refraction unchanged.
struct AtmosphereConditions {
  double pressure_mbar = 1010.0;
  double temperature_c = 10.0;
};

struct SolarPosition {
  double zenith_deg = 0;       ///< apparent (refracted) zenith angle, 0 = overhead
  double elevation_deg = 0;    ///< 90° − zenith_deg
  double azimuth_deg = 0;      ///< clockwise from north: 90° east, 180° south, 270° west
  double declination_deg = 0;  ///< apparent declination
  double right_ascension_deg = 0;
  double equation_of_time_min = 0;
  double hour_angle_deg = 0;
  double julian_day = 0;
};

/// The Julian day (UT) of the local date and time: Meeus eq. 7.1 for the Gregorian calendar.
double julian_day(const LocalDateTime& when);

/// The sun's apparent position by the NOAA equations above.
SolarPosition noaa_solar_position(const LocalDateTime& when, const GeographicLocation& where,
                                  const AtmosphereConditions& air = {});

}  // namespace rimu
