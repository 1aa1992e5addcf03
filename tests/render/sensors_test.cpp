// Sensors (render/sensors/): the "sensors" section's errors, and lux meters against closed forms: a point source
// of known intensity over a plane (E = I cos³θ / h²), a uniform sky on an unobstructed plane (E = π L), and a
// light written inline against the same light through "include".
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "input_error_check.h"
#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "render/sensors/sensor_measurement.h"
#include "render/sensors/sensor_outputs.h"
#include "sensor_test_support.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace sensors_test {

using rimu::test::kPi;
using test::sensor_scene;

test::LoadedSensors load(const json& document, const std::filesystem::path& directory = std::filesystem::current_path()) {
  return test::load_sensors(document, "sensors.json", directory);
}

SensorReadings measure(const test::LoadedSensors& loaded, uint64_t seed = 3) { return test::measure(loaded, seed); }

json point_lamp(double candela, std::vector<double> position) {
  return json{{"type", "point"}, {"position", position}, {"spectrum", {{"blackbody", 2856}}}, {"luminous_intensity_cd", candela}};
}

// A row of 4 meters at x = 0.5, 1.5, 2.5, 3.5 (y = 0) on the plane z, facing +z.
json row_grid(const std::string& name, double z) {
  return json{{"name", name}, {"origin", {0, -0.1, z}}, {"u", {1, 0, 0}}, {"v", {0, 1, 0}}, {"size", {4, 0.2}}, {"counts", {4, 1}}};
}

TEST_CASE("sensors: a point source of I cd over a plane gives I cos³θ / h² lx at every angle and height") {
  // The inverse-square and cosine laws (CIE 171:2006, the point-source cases of its section 5): with the lamp at
  // z = 3 and planes at z = 0 and z = 2, h = 3 m and 1 m, and θ from 9.5° to 74°.
  const double candela = 1000.0;
  const auto scene = load(sensor_scene(json::array({point_lamp(candela, {0, 0, 3})}),
                                     {{"samples", 512}, {"grids", {row_grid("floor", 0.0), row_grid("table", 2.0)}}}));
  const SensorReadings readings = measure(scene);
  REQUIRE(readings.grids.size() == 2);
  for (int g = 0; g < 2; ++g) {
    const double h = g == 0 ? 3.0 : 1.0;
    for (int i = 0; i < 4; ++i) {
      const double x = 0.5 + i, cos_theta = h / std::sqrt(h * h + x * x);
      CAPTURE(h);
      CAPTURE(x);
      test::check_sensor_reading(readings.grids[size_t(g)].points[size_t(i)], candela * cos_theta * cos_theta * cos_theta / (h * h));
    }
  }
  const GridReadings& floor = readings.grids[0];
  CHECK(floor.e_max_lx == doctest::Approx(floor.points[0].value));
  CHECK(floor.e_min_lx == doctest::Approx(floor.points[3].value));
  CHECK(floor.u0 == doctest::Approx(floor.e_min_lx / floor.e_avg_lx));
  SUBCASE("a meter facing away reads nothing; one facing down under the lamp reads nothing either") {
    const auto away = load(sensor_scene(json::array({point_lamp(candela, {0, 0, 3})}),
                                      {{"samples", 16},
                                       {"meters", {{{"type", "illuminance"}, {"position", {0, 0, 0}}, {"normal", {0, 0, -1}}}}}}));
    CHECK(measure(away).meters[0].value == 0.0);
  }
}

TEST_CASE("sensors: a grid lying on a floor measures the light above it, not the floor") {
  // Designers put grids on floors. The receptor's rays leave on its normal side, so the grey floor it lies in
  // neither shadows it nor adds to it (its reflection goes up, away from an upward meter on it): I cos³θ / h².
  const double candela = 1000.0, h = 2.0;
  const auto scene = load(sensor_scene(json::array({point_lamp(candela, {0, 0, h})}),
                                     {{"samples", 256}, {"grids", {row_grid("floor", 0.0)}}},
                                     json::array({{{"type", "quad"},
                                                   {"vertices", {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}}},
                                                   {"material", "grey"}}})));
  const SensorReadings readings = measure(scene);
  for (int i = 0; i < 4; ++i) {
    const double x = 0.5 + i, cos_theta = h / std::sqrt(h * h + x * x);
    CAPTURE(x);
    test::check_sensor_reading(readings.grids[0].points[size_t(i)], candela * cos_theta * cos_theta * cos_theta / (h * h));
  }
}

TEST_CASE("sensors: a uniform sky of luminance L on an unobstructed upward plane gives π L lx") {
  // E = ∫ L cos θ dω over the hemisphere = π L. Both techniques (the sky sampled as a light, and cosine directions
  // that escape to it) carry weight here, so this checks their MIS weights sum to one.
  const double luminance_nt = 1000.0;
  const auto scene = load(sensor_scene(
      json::array({{{"type", "environment"}, {"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", luminance_nt}}}),
      {{"samples", 256},
       {"grids", {{{"origin", {-1, -1, 0}}, {"u", {1, 0, 0}}, {"v", {0, 1, 0}}, {"size", {2, 2}}, {"spacing", 1.0}}}},
       {"meters", {{{"name", "up"}, {"type", "luminance"}, {"position", {0, 0, 0}}, {"direction", {0.3, 0.2, 1}}}}}}));
  const SensorReadings readings = measure(scene);
  REQUIRE(readings.grids[0].points.size() == 4);
  for (const MeterReading& r : readings.grids[0].points) test::check_sensor_reading(r, kPi * luminance_nt);
  test::check_sensor_reading(readings.meters[0], luminance_nt);
  CHECK(readings.grids[0].u0 == doctest::Approx(1.0).epsilon(0.05));
}

TEST_CASE("sensors: lux of a light written inline equals the same light through \"include\"") {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "rimu_sensors_include_test";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "lamp.json") << json{{"type", "point"}, {"spectrum", {{"blackbody", 3000}}},
                                              {"luminous_power_lm", 800}}.dump();
  const json sensors = {{"samples", 64}, {"grids", {row_grid("floor", 0.0)}}};
  const auto inline_scene = load(sensor_scene(json::array({{{"type", "point"}, {"position", {0, 0, 2.5}},
                                                          {"spectrum", {{"blackbody", 3000}}}, {"luminous_power_lm", 800}}}),
                                            sensors),
                                 folder);
  const auto included = load(
      sensor_scene(json::array({{{"include", "lamp.json"}, {"position", {0, 0, 2.5}}}}), sensors), folder);
  const SensorReadings a = measure(inline_scene), b = measure(included);
  for (size_t i = 0; i < 4; ++i) {
    CAPTURE(i);
    CHECK(a.grids[0].points[i].value > 0.0);
    CHECK(a.grids[0].points[i].value == doctest::Approx(b.grids[0].points[i].value).epsilon(1e-12));
  }
  std::filesystem::remove_all(folder);
}

TEST_CASE("sensors: the readings depend on the seed and sample count, not on the threads") {
  const auto scene = load(sensor_scene(json::array({point_lamp(100, {0.3, 0.2, 1.5})}),
                                     {{"samples", 32}, {"grids", {row_grid("floor", 0.0)}}},
                                     json::array({{{"type", "quad"},
                                                   {"vertices", {{-5, -5, -0.01}, {5, -5, -0.01}, {5, 5, -0.01}, {-5, 5, -0.01}}},
                                                   {"material", "grey"}}})));
  SensorMeasureOptions one;
  one.samples = 32;
  one.threads = 1;
  SensorMeasureOptions all = one;
  all.threads = 0;
  const SensorReadings a = measure_sensors(*scene.scene, scene.sensors, test::library().photopic_v(), one);
  const SensorReadings b = measure_sensors(*scene.scene, scene.sensors, test::library().photopic_v(), all);
  for (size_t i = 0; i < 4; ++i) CHECK(a.grids[0].points[i].value == b.grids[0].points[i].value);
}

TEST_CASE("sensors: the CSV and JSON hold every point with its standard error and the grid's U0") {
  const auto scene = load(sensor_scene(json::array({point_lamp(500, {0, 0, 2})}),
                                     {{"samples", 8}, {"grids", {row_grid("floor", 0.0)}},
                                      {"meters", {{{"name", "desk"}, {"type", "illuminance"}, {"position", {0, 0, 0}}, {"normal", {0, 0, 1}}}}}}));
  const SensorReadings readings = measure(scene);
  const std::string csv = sensor_csv(scene.sensors, readings);
  CHECK(csv.rfind("sensor,quantity,i,j,x,y,z,dx,dy,dz,value,standard_error,unit,samples\n", 0) == 0);
  CHECK(csv.find("floor,illuminance,3,0,3.5,0,0,0,0,1,") != std::string::npos);
  CHECK(csv.find("desk,illuminance,,,0,0,0,0,0,1,") != std::string::npos);
  const json doc = sensor_json(scene.sensors, readings, 8);
  CHECK(doc["grids"][0]["points"].size() == 4);
  CHECK(doc["grids"][0]["u0"].get<double>() == doctest::Approx(readings.grids[0].u0));
  CHECK(doc["meters"][0]["value"].get<double>() == doctest::Approx(readings.meters[0].value));
  CHECK(default_sensor_output_base("out/render.exr") == std::filesystem::path("out/render.sensors"));
}

TEST_CASE("sensors: bad \"sensors\" sections are refused by key, saying what was expected") {
  const json lamp = json::array({point_lamp(100, {0, 0, 2})});
  auto fails = [&](json sensors, std::initializer_list<std::string> fragments) {
    test::input_error([&] { load(sensor_scene(lamp, std::move(sensors))); }, fragments);
  };
  const json grid = row_grid("g", 0.0);
  auto with = [&](const char* key, json value) {
    json g = grid;
    if (value.is_null()) g.erase(key);
    else g[key] = std::move(value);
    return json{{"grids", {g}}};
  };
  fails(json::array(), {"/sensors", "expected an object"});
  fails({{"grid", json::array()}}, {"/sensors", "grid"});
  fails({{"samples", 0}}, {"/sensors/samples"});
  fails({{"replicates", 0}}, {"/sensors/replicates"});
  fails({{"replicates", 65}}, {"/sensors/replicates"});
  fails(with("counts", nullptr), {"/sensors/grids/0", "\"counts\"", "\"spacing\""});
  fails(with("spacing", 0.5), {"/sensors/grids/0", "not both"});
  fails(with("counts", {4}), {"/sensors/grids/0/counts", "[nu, nv]"});
  fails(with("v", {1, 1, 0}), {"/sensors/grids/0/v", "perpendicular"});
  fails(with("u", {0, 0, 0}), {"/sensors/grids/0/u", "non-zero"});
  fails(with("normal", {1, 0, 0}), {"/sensors/grids/0/normal", "u×v"});
  fails(with("size", {4, -1}), {"/sensors/grids/0/size/1"});
  fails(with("name", "a/b"), {"/sensors/grids/0/name", "letters, digits"});
  fails(with("radius", 1), {"/sensors/grids/0", "radius"});
  json tiny = grid;
  tiny.erase("counts");
  tiny["spacing"] = 1e-4;
  fails({{"grids", {tiny}}}, {"/sensors/grids/0/spacing", "at most 4096"});
  fails({{"grids", {grid, grid}}}, {"/sensors/grids/1/name", "used twice"});
  fails({{"meters", {{{"type", "lux"}, {"position", {0, 0, 0}}, {"normal", {0, 0, 1}}}}}}, {"/sensors/meters/0/type"});
  fails({{"meters", {{{"type", "illuminance"}, {"position", {0, 0, 0}}, {"direction", {0, 0, 1}}}}}},
        {"/sensors/meters/0", "direction"});
  fails({{"meters", {{{"type", "luminance"}, {"position", {0, 0, 0}}}}}}, {"/sensors/meters/0", "direction"});
}

}  // namespace sensors_test
