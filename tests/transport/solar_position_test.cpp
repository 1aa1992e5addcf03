// The sun's position by the NOAA solar calculator's equations (transport/lights/sky/solar_position.h) against
// published values: Meeus's example of the same low-precision solar coordinates, and the NREL SPA paper's example.
#include <doctest/doctest.h>

#include <cmath>

#include "transport/lights/sky/solar_position.h"

using namespace rimu;

TEST_CASE("solar position: Meeus Example 25.a, 1992 October 13 0h: the same equations to 1e-5 degrees") {
  // Meeus, "Astronomical Algorithms" (2nd ed., 1998), Example 25.a (the low-accuracy method NOAA uses): JD
  // 2448908.5, apparent α = 13h13m31.4s = 198.38083°, δ = −7°47′6″ = −7.78507°.
  const SolarPosition p = noaa_solar_position({1992, 10, 13, 0.0, 0.0}, {0.0, 0.0});
  CHECK(p.julian_day == 2448908.5);
  CHECK(std::abs(p.right_ascension_deg - 198.38083) < 1e-4);
  CHECK(std::abs(p.declination_deg - (-7.78507)) < 1e-5);
}

TEST_CASE("solar position: the NREL SPA paper's example (Golden CO, 17 October 2003 12:30:30 MST) within 0.01 degrees") {
  // Reda & Andreas, NREL/TP-560-34302 (2008), Table A5.1: JD 2452930.312847, observer hour angle H = 11.105902°,
  // geocentric α = 202.22741°, δ = −9.31434°, topocentric zenith 50.11162° and azimuth 194.34024° (from north,
  // eastward), at 820 mbar and 11 °C. NOAA's low-precision equations (no ΔT, no parallax) reach SPA's values to
  // 0.004° here, inside their stated one arc-minute; the test holds them to the 0.01° target.
  const LocalDateTime when{2003, 10, 17, 12.0 + 30.0 / 60.0 + 30.0 / 3600.0, -7.0};
  const SolarPosition p = noaa_solar_position(when, {39.742476, -105.1786}, {820.0, 11.0});
  CHECK(p.julian_day == doctest::Approx(2452930.312847).epsilon(1e-12));
  CAPTURE(p.zenith_deg);
  CAPTURE(p.azimuth_deg);
  CHECK(std::abs(p.zenith_deg - 50.11162) < 0.01);
  CHECK(std::abs(p.azimuth_deg - 194.34024) < 0.01);
  CHECK(std::abs(p.elevation_deg - (90.0 - 50.11162)) < 0.01);
  CHECK(std::abs(p.hour_angle_deg - 11.105902) < 0.01);
  CHECK(std::abs(p.right_ascension_deg - 202.22741) < 0.01);
  CHECK(std::abs(p.declination_deg - (-9.31434)) < 0.01);
  // Refraction depends on the air: at standard air (1010 mbar, 10 °C) the sun appears higher than at 820 mbar.
  const SolarPosition standard_air = noaa_solar_position(when, {39.742476, -105.1786});
  CHECK(standard_air.zenith_deg < p.zenith_deg);
  CHECK(p.zenith_deg - standard_air.zenith_deg < 0.01);  // ~19″ × 0.19
}

TEST_CASE("solar position: noon and midnight, north and south") {
  // Local solar noon at the March equinox on the equator, Greenwich: nearly overhead (|δ| < 0.5°, EoT ~ −7 min).
  const SolarPosition noon = noaa_solar_position({2024, 3, 20, 12.0, 0.0}, {0.0, 0.0});
  CHECK(noon.elevation_deg > 87.0);
  // Midnight: below the horizon, with the refraction formula's below-horizon branch finite.
  const SolarPosition midnight = noaa_solar_position({2024, 6, 21, 0.0, 1.0}, {48.85, 2.35});
  CHECK(midnight.elevation_deg < -10.0);
  CHECK(std::isfinite(midnight.azimuth_deg));
  // Paris at the June solstice, 13:50 CEST (UTC+2): near the meridian, the sun is south and 64.7° high (90 − 48.85
  // + 23.44, plus refraction).
  const SolarPosition paris = noaa_solar_position({2024, 6, 21, 13.0 + 50.0 / 60.0, 2.0}, {48.85, 2.35});
  CHECK(std::abs(paris.azimuth_deg - 180.0) < 5.0);
  CHECK(std::abs(paris.elevation_deg - (90.0 - 48.85 + 23.44)) < 0.2);
  // Sydney at solar noon in January (13:04 AEDT, UTC+11: 151.21° E and an equation of time of −9 min): due north.
  const SolarPosition sydney = noaa_solar_position({2024, 1, 15, 13.0 + 4.0 / 60.0, 11.0}, {-33.87, 151.21});
  CHECK(std::min(sydney.azimuth_deg, 360.0 - sydney.azimuth_deg) < 5.0);
  // Morning is east, afternoon west.
  CHECK(noaa_solar_position({2024, 6, 21, 8.0, 2.0}, {48.85, 2.35}).azimuth_deg < 180.0);
  CHECK(noaa_solar_position({2024, 6, 21, 18.0, 2.0}, {48.85, 2.35}).azimuth_deg > 180.0);
}
