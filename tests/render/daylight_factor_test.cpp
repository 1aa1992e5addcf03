// Daylight factor grids (render/sensors/daylight_factor.h) under the CIE standard overcast sky: an unobstructed
// point reads DF = 100 %, a point at the foot of a tall black wall 50 % (the overcast sky is azimuthally uniform, so
// the wall hides exactly half of the cosine-weighted sky from either side; the wall is 2 km tall and wide and the
// points 1 cm from it, so the sky seen past its edges is below 1e-5 of the hemisphere). Tolerance: 4.5 standard errors (false alarm
// 7e-6 under the normal approximation, fixed seeds); errors name the grid's key.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "render/sensors/daylight_factor.h"
#include "render/sensors/sensor_measurement.h"
#include "render/sensors/sensor_outputs.h"
#include "spectral/error.h"
#include "sensor_test_support.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace daylight_factor_test {

const json kOvercast = {{"type", "cie_sky"}, {"sky_type", 1}, {"diffuse_horizontal_illuminance_lx", 10000}};

// One meter facing up (+y) at (x, 0, 0): u along z, v along x, so u × v = +y.
json point_grid(const std::string& name, double x) {
  return {{"name", name}, {"origin", {x - 0.005, 0, -0.005}}, {"u", {0, 0, 1}}, {"v", {1, 0, 0}},
          {"size", {0.01, 0.01}}, {"counts", {1, 1}}, {"daylight_factor", true}};
}

json scene_with(json lights, json grids, json shapes = json::array()) {
  return {{"camera", {{"from", {0, 1, 5}}, {"to", {0, 0, 0}}}},
          {"materials", {{"black", {{"type", "diffuse"}, {"reflectance", 0.0}}}}},
          {"lights", std::move(lights)},
          {"shapes", std::move(shapes)},
          {"sensors", {{"samples", 4096}, {"grids", std::move(grids)}}}};
}

test::LoadedSensors load(const json& document) { return test::load_sensors(document, "df.json"); }

SensorReadings measure(const test::LoadedSensors& loaded) { return test::measure(loaded, 5); }

void check_df(const MeterReading& df, double expected_percent) { test::check_sensor_reading(df, expected_percent); }

TEST_CASE("daylight factor: 100 % unobstructed, 50 % at the foot of a tall black wall, under the CIE overcast sky") {
  const json wall = {{"type", "quad"}, {"material", "black"},
                     {"vertices", {{0, 0, -1000}, {0, 0, 1000}, {0, 2000, 1000}, {0, 2000, -1000}}}};
  // Unobstructed (nothing in the scene) and by the wall: two scenes, since the wall hides half the sky from any
  // point on its side near enough to it.
  const test::LoadedSensors open_scene = load(scene_with(json::array({kOvercast}), {point_grid("open", 0.0)}));
  const SensorReadings open_readings = measure(open_scene);
  REQUIRE(open_readings.grids[0].daylight_factor);
  const DaylightFactors& open = *open_readings.grids[0].daylight_factor;
  // E_out is the sky's own calibration: the 10000 lx it was given.
  CHECK(open.outdoor_illuminance_lx == doctest::Approx(10000.0).epsilon(1e-9));
  check_df(open.points_percent[0], 100.0);
  CHECK(open.df_avg_percent == doctest::Approx(open.points_percent[0].value));
  MESSAGE("unobstructed: DF " << open.points_percent[0].value << " % +- " << open.points_percent[0].standard_error);

  const test::LoadedSensors loaded = load(scene_with(json::array({kOvercast}), {point_grid("behind", -0.01), point_grid("wall", 0.01)},
                                        json::array({wall})));
  const SensorReadings readings = measure(loaded);
  REQUIRE(readings.grids.size() == 2);
  const MeterReading& by_wall = readings.grids[1].daylight_factor->points_percent[0];
  check_df(by_wall, 50.0);
  check_df(readings.grids[0].daylight_factor->points_percent[0], 50.0);  // the wall's other side
  MESSAGE("by the wall: DF " << by_wall.value << " % +- " << by_wall.standard_error);

  // The outputs: daylight_factor rows in % after the grid's lux rows, and the grid's DF statistics in the JSON.
  const std::string csv = sensor_csv(loaded.sensors, readings);
  CHECK(csv.find("wall,illuminance,0,0,") != std::string::npos);
  CHECK(csv.find("wall,daylight_factor,0,0,") != std::string::npos);
  CHECK(csv.find(",%,4096\n") != std::string::npos);
  const json doc = sensor_json(loaded.sensors, readings, 4096);
  CHECK(doc["grids"][0]["daylight_factor"]["outdoor_illuminance_lx"].get<double>() == doctest::Approx(10000.0));
  CHECK(doc["grids"][1]["points"][0]["daylight_factor_percent"].get<double>() ==
        doctest::Approx(readings.grids[1].daylight_factor->points_percent[0].value));
}

TEST_CASE("daylight factor: a scene without the overcast sky alone is refused, naming the grid's key") {
  const auto refused = [](json lights, const std::string& expected) {
    const test::LoadedSensors loaded = load(scene_with(std::move(lights), {point_grid("g", 0.0)}));
    CHECK_THROWS_WITH_AS(
        check_daylight_factor_grids(*loaded.scene, loaded.sensors, test::library().photopic_v(), "df.json"),
        doctest::Contains("/sensors/grids/0/daylight_factor"), InputError);
    CHECK_THROWS_WITH_AS(
        check_daylight_factor_grids(*loaded.scene, loaded.sensors, test::library().photopic_v(), "df.json"),
        doctest::Contains(expected.c_str()), InputError);
    // measure_sensors refuses it too, before any sample.
    CHECK_THROWS_AS(measure(loaded), InputError);
  };
  refused(json::array({{{"type", "cie_sky"}, {"sky_type", 3}, {"diffuse_horizontal_illuminance_lx", 10000}}}),
          "sky_type 1");
  refused(json::array({kOvercast, {{"type", "point"}, {"name", "lamp"}, {"position", {0, 2, 0}},
                                   {"spectrum", {{"blackbody", 3000}}}, {"luminous_intensity_cd", 100}}}),
          "'lamp'");
  refused(json::array({{{"type", "point"}, {"position", {0, 2, 0}}, {"spectrum", {{"blackbody", 3000}}},
                        {"luminous_intensity_cd", 100}}}),
          "needs a CIE overcast sky");
  // A key of the wrong type.
  json grid = point_grid("g", 0.0);
  grid["daylight_factor"] = "yes";
  CHECK_THROWS_WITH_AS(load(scene_with(json::array({kOvercast}), {grid})),
                       doctest::Contains("/sensors/grids/0/daylight_factor"), InputError);
}

}  // namespace daylight_factor_test
