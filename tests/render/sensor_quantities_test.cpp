// The sensors' extra spectral quantities: scotopic illuminance (V'(λ), K'_m = 1700 lm/W) and melanopic EDI
// (CIE S 026/E:2018: ∫ E s_mel dλ / K_mel,v^D65). The melanopic table (data/cmf/cie_s026_melanopic_1nm.csv) is
// checked against its definition (D65's DER is 1) and a published DER of illuminant A; the meters against the
// spectral integrals of the light they see.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "input_error_check.h"
#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "render/sensors/sensor_measurement.h"
#include "render/sensors/sensor_outputs.h"
#include "render/sensors/sensor_plan.h"
#include "spectral/photometry/photometry.h"
#include "sensor_test_support.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

using rimu::test::kPi;

}  // namespace

TEST_CASE("melanopic DER: D65 is 1 by construction, illuminant A as published") {
  SpectralLibrary& library = test::library();
  const TabulatedSpectrum& v = library.photopic_v();
  const TabulatedSpectrum& s_mel = library.melanopic_action_spectrum();
  CHECK(s_mel.value(490.0) == 1.0f);  // the table's peak
  CHECK(s_mel.value(379.0) == 0.0f);  // defined on 380-780 nm only
  // K_mel,v^D65 = 1.3262 mW/lm is D65's own melanopic efficacy rounded to 5 digits: ±0.00005/1.3262 = ±3.8e-5.
  CHECK(melanopic_daylight_efficacy_ratio(*library.illuminant("D65"), v, s_mel) == doctest::Approx(1.0).epsilon(3.8e-5));
  // Illuminant A: 100 lx has a melanopic EDI of 49.581 lx in the Lighting Toolbox's CIE S 026 example
  // (frudawski.de, ciemedi), i.e. DER 0.49581; implementations differ in the 4th digit (the same toolbox's later
  // version prints 49.743 with another normalisation of A), so 2e-4 absolute (0.04 %) is asked here.
  CHECK(melanopic_daylight_efficacy_ratio(*library.illuminant("A"), v, s_mel) == doctest::Approx(0.49581).epsilon(4e-4));
}

TEST_CASE("sensor quantities: scotopic lux and melanopic EDI of a uniform sky match its spectrum's integrals") {
  SpectralLibrary& library = test::library();
  const double luminance_nt = 1000.0;
  for (const char* illuminant : {"D65", "A"}) {
    CAPTURE(illuminant);
    const SpectrumPtr spectrum = library.illuminant(illuminant);
    // Under a uniform sky E = π L, so its scotopic and melanopic values are E times the spectrum's ratios.
    const double e_lx = kPi * luminance_nt;
    const double scotopic_ratio = scotopic_luminous_efficacy_lm_W(*spectrum, library.scotopic_v_prime()).lm_W /
                                  luminous_efficacy_of_radiation_lm_W(*spectrum, library.photopic_v()).lm_W;
    const double der = melanopic_daylight_efficacy_ratio(*spectrum, library.photopic_v(), library.melanopic_action_spectrum());
    const json document = test::sensor_scene(
        json::array({{{"type", "environment"}, {"spectrum", {{"illuminant", illuminant}}}, {"luminance_nt", luminance_nt}}}),
        {{"samples", 2048},
         {"quantities", {"photopic", "scotopic", "melanopic_edi"}},
         {"grids", {{{"name", "plane"}, {"origin", {-1, -1, 0}}, {"u", {1, 0, 0}}, {"v", {0, 1, 0}}, {"size", {2, 2}}, {"counts", {2, 1}}}}},
         {"meters", {{{"name", "cyl"}, {"type", "cylindrical"}, {"position", {0, 0, 0}}, {"axis", {0, 0, 1}}},
                     {{"name", "eye"}, {"type", "luminance"}, {"position", {0, 0, 0}}, {"direction", {1, 0, 0}}}}}});
    const auto scene = load_scene(document, "quantities.json", std::filesystem::current_path(), library);
    const SensorSettings sensors = scene_sensors(document, "quantities.json");
    SensorMeasureOptions options;
    options.samples = sensors.samples;
    options.seed = 11;
    options.scotopic_v_prime = &library.scotopic_v_prime();
    options.melanopic = &library.melanopic_action_spectrum();
    const SensorReadings r = measure_sensors(*scene, sensors, library.photopic_v(), options);
    REQUIRE(r.grids[0].scotopic_points.size() == 2);
    REQUIRE(r.grids[0].melanopic_points.size() == 2);
    REQUIRE(r.meters_melanopic.size() == 2);
    for (size_t k = 0; k < 2; ++k) {
      test::check_sensor_reading(r.grids[0].points[k], e_lx);
      test::check_sensor_reading(r.grids[0].scotopic_points[k], e_lx * scotopic_ratio);
      test::check_sensor_reading(r.grids[0].melanopic_points[k], e_lx * der);
    }
    test::check_sensor_reading(r.meters_scotopic[0], e_lx * scotopic_ratio);
    test::check_sensor_reading(r.meters_melanopic[0], e_lx * der);
    test::check_sensor_reading(r.meters_scotopic[1], luminance_nt * scotopic_ratio);
    test::check_sensor_reading(r.meters_melanopic[1], luminance_nt * der);

    const std::string csv = sensor_csv(sensors, r);
    CHECK(csv.find("\nplane,scotopic_illuminance,1,0,") != std::string::npos);
    CHECK(csv.find("\nplane,melanopic_edi,0,0,") != std::string::npos);
    CHECK(csv.find("\ncyl,melanopic_edi_cylindrical,,,") != std::string::npos);
    CHECK(csv.find("\neye,melanopic_edl,,,") != std::string::npos);
    CHECK(csv.find("\neye,scotopic_luminance,,,") != std::string::npos);
    const json doc = sensor_json(sensors, r, 2048);
    CHECK(doc["grids"][0]["melanopic_edi"]["e_avg"].get<double>() ==
          doctest::Approx((r.grids[0].melanopic_points[0].value + r.grids[0].melanopic_points[1].value) / 2));
    CHECK(doc["grids"][0]["points"][1]["scotopic"]["value"].get<double>() == r.grids[0].scotopic_points[1].value);
    CHECK(doc["meters"][1]["melanopic_edi"]["quantity"] == "melanopic_edl");
  }
}

TEST_CASE("sensor quantities: only what is asked for is measured, and bad lists are refused") {
  const json lamp = json::array({{{"type", "point"}, {"position", {0, 0, 2}}, {"spectrum", {{"blackbody", 3000}}},
                                  {"luminous_intensity_cd", 100}}});
  const json meter = {{"type", "illuminance"}, {"position", {0, 0, 0}}, {"normal", {0, 0, 1}}};
  const json plain = test::sensor_scene(lamp, {{"samples", 8}, {"meters", {meter}}});
  const auto scene = load_scene(plain, "q.json", std::filesystem::current_path(), test::library());
  SensorMeasureOptions options;
  options.samples = 8;
  const SensorReadings r = measure_sensors(*scene, scene_sensors(plain, "q.json"), test::library().photopic_v(), options);
  CHECK(r.meters_scotopic.empty());
  CHECK(r.meters_melanopic.empty());
  CHECK(sensor_csv(scene_sensors(plain, "q.json"), r).find("scotopic") == std::string::npos);

  auto fails = [&](json quantities, std::initializer_list<std::string> fragments) {
    test::input_error(
        [&] {
          load_scene(test::sensor_scene(lamp, {{"quantities", quantities}, {"meters", {meter}}}), "q.json",
                     std::filesystem::current_path(), test::library());
        },
        fragments);
  };
  fails("scotopic", {"/sensors/quantities", "expected an array"});
  fails({"photopic", "melanopic"}, {"/sensors/quantities/1", "melanopic_edi"});
  fails({"scotopic", "scotopic"}, {"/sensors/quantities/1", "twice"});
}

TEST_CASE("sensors: the false-colour plan of a grid's scotopic lux or melanopic EDI draws those values, named") {
  IlluminanceGrid grid;
  grid.name = "floor";
  grid.size_u_m = 2.0f;
  grid.size_v_m = 1.0f;
  grid.count_u = 2;
  grid.count_v = 1;
  GridReadings readings;
  readings.points = {{100.0, 1.0, 16}, {200.0, 1.0, 16}};
  readings.scotopic_points = {{250.0, 2.0, 16}, {470.0, 2.0, 16}};
  const GnuplotJob scotopic = grid_plan_job(grid, readings, PlanQuantity::scotopic);
  CHECK(scotopic.commands.find("Esmin 250.0 lx, Esavg 360.0 lx, Esmax 470.0 lx, U0 0.69") != std::string::npos);
  CHECK(scotopic.commands.find("scotopic illuminance (scotopic lx)") != std::string::npos);
  REQUIRE(scotopic.data_files.size() == 1);
  CHECK(scotopic.data_files[0].second.find(" 470\n") != std::string::npos);
  CHECK(scotopic.data_files[0].second.find(" 200\n") == std::string::npos);
  const GnuplotJob photopic = grid_plan_job(grid, readings);
  CHECK(photopic.commands.find("Emin 100.0 lx, Eavg 150.0 lx, Emax 200.0 lx, U0 0.67") != std::string::npos);
  // No melanopic points were measured: asking for their plan is a programming error, not an empty plan.
  CHECK_THROWS_AS(grid_plan_job(grid, readings, PlanQuantity::melanopic_edi), std::logic_error);
  CHECK(grid_plan_path("/tmp/office.sensors", grid, PlanQuantity::melanopic_edi).string() ==
        "/tmp/office.sensors.floor.melanopic_edi.png");
}
