// The daylight lights of the JSON scene (render/scene/scene_daylight.h): a CIE sky calibrated by diffuse horizontal
// illuminance or zenith luminance reads its lux on a light meter, a sun placed by date and place points where the
// solar position says and gives its lux, a sun below the horizon warns, and bad daylight keys are named.
// Tolerances: five standard errors of the meter's Monte Carlo estimate (tests/render/light_units_render_test.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "meter_reading_check.h"
#include "input_error_check.h"
#include "render/reports/light_meter.h"
#include "render/scene/scene.h"
#include "spectral/photometry/light_units.h"
#include "test_support.h"
#include "transport/lights/sky/cie_sky_light.h"
#include "transport/lights/sky/solar_position.h"

using namespace rimu;
using nlohmann::json;

namespace daylight_test {

using rimu::test::kPi;

json scene_with(json lights) {
  return json{{"camera", {{"from", {0, 1, 3}}, {"to", {0, 1, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 40}}},
              {"materials", {{"grey", {{"type", "diffuse"}, {"reflectance", 0.5}}}}},
              {"lights", std::move(lights)},
              {"shapes", json::array()}};
}

std::unique_ptr<Scene> load(const json& document) {
  return load_scene(document, "test scene", std::filesystem::current_path(), test::library());
}

MeterReading meter(const Scene& scene, Vec3 normal, int samples = 20000) {
  return measure_illuminance_lx(scene.transport_view(), {0, 0, 0}, normal, test::library().photopic_v(), samples, 11);
}

using test::check_reading;

const json kGolden = {{"latitude_deg", 39.742476}, {"longitude_deg", -105.1786}, {"date", "2003-10-17"},
                      {"time", "12:30:30"}, {"utc_offset_h", -7}};

TEST_CASE("a CIE overcast sky calibrated to 10000 lx gives 10000 lx on a horizontal meter") {
  const auto scene = load(scene_with(json::array(
      {{{"type", "cie_sky"}, {"sky_type", 1}, {"diffuse_horizontal_illuminance_lx", 10000}}})));
  check_reading(meter(*scene, {0, 1, 0}), 10000.0);
  CHECK(scene->warnings.empty());
  // Nothing comes from below: a meter facing down reads 0.
  CHECK(meter(*scene, {0, -1, 0}, 2000).value == 0.0);
}

TEST_CASE("a CIE clear sky at a date and place, calibrated by illuminance or zenith luminance, reads its lux") {
  for (int type : {12, 15}) {
    CAPTURE(type);
    const auto scene = load(scene_with(json::array({{{"type", "cie_sky"}, {"sky_type", type}, {"sun_position", kGolden},
                                                     {"cct", 9000}, {"diffuse_horizontal_illuminance_lx", 20000}}})));
    check_reading(meter(*scene, {0, 1, 0}), 20000.0);
    // The same sky given by its zenith luminance: E = L_z ∫ L/L_z cos θ dω.
    const auto& sky = dynamic_cast<const CieSkyLight&>(*scene->lights[0]);
    const double zenith_nt = 20000.0 / sky.integrals().cosine_weighted_sr;
    const auto by_luminance = load(scene_with(json::array({{{"type", "cie_sky"}, {"sky_type", type},
                                                            {"sun_position", kGolden}, {"cct", 9000},
                                                            {"zenith_luminance_nt", zenith_nt}}})));
    check_reading(meter(*by_luminance, {0, 1, 0}), 20000.0);
    // The zenith's luminance is what was asked: K_m Σ L_z(λ) V(λ) Δλ.
    const LightSpectrum& zenith = *by_luminance->lights[0]->emitted_spectrum();
    CHECK(zenith.scale() * shape_integrals(*zenith.shape(), test::library().photopic_v()).luminous ==
          doctest::Approx(zenith_nt).epsilon(1e-9));
    // The sky is brighter on the side of the sun (south-south-west at Golden that noon: azimuth 194°).
    const SolarPosition sun = noaa_solar_position({2003, 10, 17, 12.5 + 30.0 / 3600, -7}, {39.742476, -105.1786});
    // Towards azimuth A the horizontal direction is north cos A + east sin A = (sin A, 0, −cos A) here.
    const float sin_a = float(std::sin(sun.azimuth_deg * kPi / 180)), cos_a = float(std::cos(sun.azimuth_deg * kPi / 180));
    CHECK(sky.relative_luminance(normalize(Vec3{sin_a, 0.5f, -cos_a})) >
          sky.relative_luminance(normalize(Vec3{-sin_a, 0.5f, cos_a})));
  }
}

TEST_CASE("a sun placed by date and place points at the solar position and gives its lux normal to it") {
  const auto scene = load(scene_with(json::array({{{"type", "sun"}, {"sun_position", kGolden},
                                                   {"spectrum", {{"daylight", 5500}}}, {"illuminance_lx", 80000}}})));
  CHECK(scene->warnings.empty());
  // Default frame: y up, north −z, east +x. SPA: zenith 50.11°, azimuth 194.34° (south-south-west).
  const SolarPosition p = noaa_solar_position({2003, 10, 17, 12.5 + 30.0 / 3600, -7}, {39.742476, -105.1786});
  const double h = p.elevation_deg * kPi / 180, a = p.azimuth_deg * kPi / 180;
  const Vec3 to_sun{float(std::cos(h) * std::sin(a)), float(std::sin(h)), float(-std::cos(h) * std::cos(a))};
  CHECK(to_sun.z > 0.9f * std::cos(h));  // south is +z
  check_reading(meter(*scene, to_sun, 4000), 80000.0);
  // On the ground: E cos Z.
  check_reading(meter(*scene, {0, 1, 0}, 4000), 80000.0 * std::cos((90.0 - p.elevation_deg) * kPi / 180));
}

TEST_CASE("azimuth and elevation, up and north: east is north x up") {
  const json sun = {{"type", "sun"}, {"sun_position", {{"azimuth_deg", 90}, {"elevation_deg", 0.5}}},
                    {"spectrum", {{"blackbody", 5800}}}, {"illuminance_lx", 1000}, {"angular_diameter_deg", 0}};
  const auto y_up = load(scene_with(json::array({sun})));
  check_reading(meter(*y_up, {1, 0, 0}, 200), 1000.0 * std::cos(0.5 * kPi / 180));
  json z_up = sun;
  z_up["up"] = {0, 0, 1};
  z_up["north"] = {0, 1, 0};  // east = north × up = +x
  check_reading(meter(*load(scene_with(json::array({z_up}))), {1, 0, 0}, 200), 1000.0 * std::cos(0.5 * kPi / 180));
}

TEST_CASE("a sun below the horizon warns at load, naming the light, and gives no light") {
  json night = kGolden;
  night["time"] = "23:30";
  const auto scene = load(scene_with(json::array({{{"type", "sun"}, {"name", "key sun"}, {"sun_position", night},
                                                   {"spectrum", {{"daylight", 5500}}}, {"illuminance_lx", 80000}}})));
  REQUIRE(scene->warnings.size() >= 1);
  const std::string& warning = scene->warnings[0];
  CAPTURE(warning);
  CHECK(warning.find("'key sun' (/lights/0)") != std::string::npos);
  CHECK(warning.find("below the horizon") != std::string::npos);
  CHECK(warning.find("2003-10-17 23:30") != std::string::npos);
  CHECK(warning.find("gives no light") != std::string::npos);
  CHECK(meter(*scene, {0, -1, 0}, 200).value == 0.0);
  // Given by elevation: the same warning; a CIE sky with its sun below the horizon warns too.
  const auto given = load(scene_with(json::array(
      {{{"type", "cie_sky"}, {"sky_type", 12}, {"sun_position", {{"azimuth_deg", 0}, {"elevation_deg", -3}}},
        {"diffuse_horizontal_illuminance_lx", 100}}})));
  REQUIRE(given->warnings.size() >= 1);
  CHECK(given->warnings[0].find("3.00° below the horizon") != std::string::npos);
}

TEST_CASE("bad daylight keys are named") {
  auto sky = [](json extra) {
    json l = {{"type", "cie_sky"}, {"sky_type", 12}, {"sun_position", kGolden}, {"diffuse_horizontal_illuminance_lx", 1}};
    for (auto& [k, v] : extra.items()) l[k] = v;
    return scene_with(json::array({l}));
  };
  test::input_error([&] { load(sky({{"sky_type", 16}})); }, {"/lights/0/sky_type"});
  test::input_error([&] { load(sky({{"zenith_luminance_nt", 5}})); }, {"exactly one of"});
  test::input_error([&] { load(sky({{"cct", 2000}})); }, {"/lights/0/cct"});
  json no_sun = sky({});
  no_sun["lights"][0].erase("sun_position");
  test::input_error([&] { load(no_sun); }, {"depends on where the sun is"});
  json bad_date = kGolden;
  bad_date["date"] = "2003-02-29";
  test::input_error([&] { load(sky({{"sun_position", bad_date}})); }, {"/lights/0/sun_position/date", "not a date"});
  json bad_time = kGolden;
  bad_time["time"] = "25:00";
  test::input_error([&] { load(sky({{"sun_position", bad_time}})); }, {"/lights/0/sun_position/time"});
  json mixed = kGolden;
  mixed["elevation_deg"] = 30;
  test::input_error([&] { load(sky({{"sun_position", mixed}})); }, {"/lights/0/sun_position"});
  test::input_error([&] { load(sky({{"north", {0, 1, 0}}})); }, {"/lights/0/north", "perpendicular"});
  // An overcast sky needs no sun.
  json overcast = sky({{"sky_type", 1}});
  overcast["lights"][0].erase("sun_position");
  CHECK(load(overcast)->lights.size() == 1);
}

}  // namespace daylight_test
