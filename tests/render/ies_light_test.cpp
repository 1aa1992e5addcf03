// IES LM-63 photometric files: parsing (type C, TILT=NONE/INCLUDE), clear errors with the line for malformed
// files, the symmetry expansions, and the "ies" scene light measured by the light meter: E = I(γ) cos θ / r² on a
// horizontal sensor below the lamp. Meter tolerances: five standard errors (false alarm < 1e-6 under the normal
// approximation); table values are exact arithmetic (rounding tolerances).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <unistd.h>

#include "meter_reading_check.h"
#include "render/scene/ies_file.h"
#include "render/reports/light_meter.h"
#include "render/scene/scene.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/photometry/emitter_photometry.h"
#include "spectral/error.h"
#include "test_support.h"
#include "transport/lights/goniometric_light.h"

using namespace rimu;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using rimu::test::kPi;
double rad(double deg) { return deg * kPi / 180.0; }

// Axially symmetric downlight: 500 cd (×2 multiplier = 1000) to 30°, linear to 0 at 60°, dark to 90°. Its flux
// is 2π·1000·[(1 − cos 30°) + cos 30° − (sin 60° − sin 30°)/(π/6)] = 1890.9 lm, written as the lamp lumens.
const char* kAxial = R"(IESNA:LM-63-2002
[TEST] rimu test
[MANUFAC] none
TILT=NONE
1 1890.9 2.0 4 1 1 2 0.1 0.1 0
1.0 1.0 15
0 30 60 90
0
500 500 0 0
)";

// Quadrant symmetric (0-90°), in LM-63-1995 form with TILT=INCLUDE (multiplier 1 at 0°), values spread over lines.
const char* kQuadrant = R"(IESNA:LM-63-1995
[TEST] quadrant
TILT=INCLUDE
1
3
0 45 90
1.0 0.8 0.5
1 -1 1 3 3 1 2 0 0 0
1 1 20
0 45 90
0 45 90
100 80 0
100 60
0 100 40 0
)";

double analytic_axial_lumens() {
  return 2 * kPi * 1000 * ((1 - std::cos(rad(30))) + std::cos(rad(30)) - (std::sin(rad(60)) - std::sin(rad(30))) / rad(30));
}

struct TempFolder {
  fs::path path = fs::temp_directory_path() / ("rimu-ies-test-" + std::to_string(::getpid()));
  TempFolder() { fs::create_directories(path); }
  ~TempFolder() { fs::remove_all(path); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path / name) << text; }
};

std::unique_ptr<Scene> scene_with_light(const TempFolder& folder, json light) {
  const json document{{"camera", {{"from", {0, 1, 5}}, {"to", {0, 0, 0}}}}, {"lights", json::array({light})}};
  return load_scene(document, "ies scene", folder.path, test::library());
}

MeterReading meter(const Scene& scene, Vec3 position) {
  return measure_illuminance_lx(scene.transport_view(), position, {0, 1, 0}, test::library().photopic_v(), 2000, 11);
}

using test::check_reading;

}  // namespace

TEST_CASE("IES type C, axially symmetric: header, candela at grid points and between, lumens") {
  const IesPhotometry ies = parse_ies(kAxial, "axial.ies");
  CHECK(ies.version == "IESNA:LM-63-2002");
  REQUIRE(ies.keywords.size() == 2);
  CHECK(ies.keywords[1].first == "MANUFAC");
  CHECK(ies.keywords[1].second == "none");
  CHECK(ies.input_watts == 15);
  CHECK(ies.rated_lamp_lumens() == 1890.9);
  const auto table = candela_distribution(ies);
  // Grid points: the file's values times the multiplier 2, in every C (axial symmetry).
  for (double c : {0.0, 77.0, 180.0, 300.0}) {
    CHECK(table->intensity_deg(0, c) == 1000.0);
    CHECK(table->intensity_deg(30, c) == 1000.0);
    CHECK(table->intensity_deg(60, c) == 0.0);
    CHECK(table->intensity_deg(45, c) == doctest::Approx(500.0).epsilon(1e-14));  // linear between 30° and 60°
  }
  CHECK(table->intensity_deg(120, 0) == 0.0);  // above the last vertical angle (90°): dark
  // The integral of the linear profile (exact) against the file's lumens, given to 0.1 lm.
  CHECK(table->integral_sr() == doctest::Approx(analytic_axial_lumens()).epsilon(1e-12));
  CHECK(std::abs(table->integral_sr() - ies.rated_lamp_lumens()) < 0.05);
  // Beam angle: the intensity halves at 45° on each side (linear from 30° to 60°): 90°.
  CHECK(ies_spread_angle_deg(*table, 0.5) == doctest::Approx(90.0).epsilon(1e-6));
}

TEST_CASE("IES type C, quadrant symmetric 0-90: the expansion to a full turn, 1995 factors and TILT=INCLUDE") {
  const IesPhotometry ies = parse_ies(kQuadrant, "quadrant.ies");
  CHECK(ies.tilt == "INCLUDE");
  CHECK(ies.tilt_factor == 1.0);
  CHECK(ies.rated_lamp_lumens() == 0.0);  // −1: absolute photometry
  const auto t = candela_distribution(ies);
  // File (γ 0, 45, 90): C0 100 80 0, C45 100 60 0, C90 100 40 0. Mirror images: C 135 = 45, 180 = 0, 270 = 90.
  CHECK(t->intensity_deg(45, 0) == 80.0);
  CHECK(t->intensity_deg(45, 90) == 40.0);
  CHECK(t->intensity_deg(45, 135) == 60.0);
  CHECK(t->intensity_deg(45, 180) == 80.0);
  CHECK(t->intensity_deg(45, 270) == 40.0);
  CHECK(t->intensity_deg(45, 315) == 60.0);
  // Bilinear in C: C 200° folds to 20°, 20/45 of the way from 80 to 60; C 300° folds to 60°.
  CHECK(t->intensity_deg(45, 200) == doctest::Approx(80.0 + (60.0 - 80.0) * 20.0 / 45.0).epsilon(1e-14));
  CHECK(t->intensity_deg(45, 300) == doctest::Approx(60.0 + (40.0 - 60.0) * 15.0 / 45.0).epsilon(1e-14));
  // Bilinear in both: (22.5°, 22.5°) is the mean of 100, 80, 100, 60.
  CHECK(t->intensity_deg(22.5, 22.5) == doctest::Approx(85.0).epsilon(1e-14));
}

TEST_CASE("IES malformed files: InputError with the file and line") {
  auto fails = [](const std::string& text, const std::string& message) {
    CAPTURE(message);
    CHECK_THROWS_WITH_AS(parse_ies(text, "bad.ies"), doctest::Contains(message.c_str()), InputError);
  };
  const std::string head = "IESNA:LM-63-2002\n[TEST] x\nTILT=NONE\n";
  // Truncated table: 2 vertical × 1 horizontal announced, one value given (the file ends on line 8).
  fails(head + "1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n100\n", "bad.ies:8: the candela table ends after 1 of 2 values");
  fails(head + "1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 60 45\n0\n1 2 3\n", "bad.ies:6: vertical angles must increase: 45 after 60");
  fails(head + "1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n100 50 7\n", "bad.ies:8: more values than the 2");
  fails(head + "1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n100 -5\n", "bad.ies:8: candela value 2 is negative");
  fails(head + "1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n100 lots\n", "bad.ies:8: expected a number for candela value 2, got 'lots'");
  fails(head + "1 -1 1 2 1 2 2 0 0 0\n1 1 10\n0 90\n0\n100 5\n", "bad.ies:4: photometric type B is not supported");
  fails(head + "1 -1 1 2 2 1 2 0 0 0\n1 1 10\n0 90\n0 30\n1 2 3 4\n", "bad.ies:7: horizontal angles must run");
  fails(head + "1 0 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n1 2\n", "bad.ies:4: the lumens per lamp must be positive, or -1");
  // One value near the largest double beside a small one: each is finite, but the table's flux (and the sampling
  // weights, which average cell corners) overflow. Must be an InputError, not the distribution's assertion.
  fails(head + "1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n1e308 100\n", "bad.ies:8: the candela values are too large");
  // 1e306 cd is absurd but representable: 16π·1e306 ≈ 5e307 is finite, so it loads with a finite flux.
  CHECK(std::isfinite(candela_distribution(parse_ies(head + "1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n1e306 100\n", "big.ies"))
                          ->integral_sr()));
  fails("IESNA:LM-63-2002\n[TEST] x\n1 -1 1 2 1\n", "bad.ies:3: no TILT= line");
  fails("IESNA:LM-63-2002\nTILT=lamp.tlt\n", "bad.ies:2: TILT=lamp.tlt");
}

TEST_CASE("an ies light measured by the light meter: E = I(gamma) cos theta / r^2 below the lamp") {
  TempFolder folder;
  folder.write("axial.ies", kAxial);
  folder.write("quadrant.ies", kQuadrant);
  SUBCASE("axial downlight 2 m above the floor") {
    const auto scene = scene_with_light(folder, {{"type", "ies"}, {"file", "axial.ies"}, {"position", {0, 2, 0}},
                                                 {"spectrum", {{"blackbody", 3000}}}});
    check_reading(meter(*scene, {0, 0, 0}), 1000.0 / 4.0);  // straight below: 1000 cd at 2 m
    // 2 m to the side: γ = θ = 45°, I = 500 cd, r² = 8: E = 500 cos 45° / 8.
    check_reading(meter(*scene, {2, 0, 0}), 500.0 * std::cos(rad(45)) / 8.0);
    // The light's radiant power times the shape's efficacy is the table's lumens.
    const double efficacy = shape_integrals(BlackbodySpectrum(3000, BlackbodySpectrum::Scale::peak_one),
                                            test::library().photopic_v()).efficacy_lm_W();
    CHECK(scene->lights[0]->total_power_w(1.0) * efficacy == doctest::Approx(analytic_axial_lumens()).epsilon(1e-9));
  }
  SUBCASE("quadrant table: C = 0° along c0_direction, C = 90° counter-clockwise seen from above") {
    const auto scene = scene_with_light(folder, {{"type", "ies"}, {"file", "quadrant.ies"}, {"position", {0, 2, 0}},
                                                 {"direction", {0, -1, 0}}, {"c0_direction", {1, 0, 0}},
                                                 {"spectrum", {{"illuminant", "D65"}}}});
    check_reading(meter(*scene, {2, 0, 0}), 80.0 * std::cos(rad(45)) / 8.0);   // C = 0°: +x
    check_reading(meter(*scene, {0, 0, -2}), 40.0 * std::cos(rad(45)) / 8.0);  // C = 90°: −z
  }
  SUBCASE("luminous_power_lm and candela_scale override the file's values") {
    const auto lm = scene_with_light(folder, {{"type", "ies"}, {"file", "axial.ies"}, {"position", {0, 2, 0}},
                                              {"spectrum", {{"blackbody", 3000}}}, {"luminous_power_lm", 500}});
    check_reading(meter(*lm, {0, 0, 0}), 1000.0 * 500.0 / analytic_axial_lumens() / 4.0);
    const auto cd = scene_with_light(folder, {{"type", "ies"}, {"file", "axial.ies"}, {"position", {0, 2, 0}},
                                              {"spectrum", {{"blackbody", 3000}}}, {"candela_scale", 0.5}});
    check_reading(meter(*cd, {0, 0, 0}), 500.0 / 4.0);
  }
  SUBCASE("errors name the scene key and the IES line") {
    folder.write("broken.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n100\n");
    CHECK_THROWS_WITH_AS(scene_with_light(folder, {{"type", "ies"}, {"file", "broken.ies"}, {"position", {0, 2, 0}},
                                                   {"spectrum", 1.0}}),
                         doctest::Contains("/lights/0/file: "), InputError);
    CHECK_THROWS_WITH_AS(scene_with_light(folder, {{"type", "ies"}, {"file", "broken.ies"}, {"position", {0, 2, 0}},
                                                   {"spectrum", 1.0}}),
                         doctest::Contains("broken.ies:7: the candela table ends after 1 of 2"), InputError);
    CHECK_THROWS_WITH_AS(scene_with_light(folder, {{"type", "ies"}, {"file", "axial.ies"}, {"position", {0, 2, 0}},
                                                   {"spectrum", 1.0}, {"luminous_power_lm", 5}, {"candela_scale", 2}}),
                         doctest::Contains("either luminous_power_lm or candela_scale"), InputError);
  }
  SUBCASE("luminous_opening: the file's disc lights the plane below as a disc, not a point") {
    // 100 cd over the lower hemisphere from a disc of 0.2 m diameter (LM-63 width = length = −0.2, height 0), 5 cm
    // above the meter: E = (2I/R²)(1 − h/√(R² + h²)) = 11,056 lx (a Lambertian disc of radiance I/(πR²)); as a point
    // the same file gives I/h² = 40,000 lx.
    folder.write("disc.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 -0.2 -0.2 0\n1 1 0\n0 90\n0\n100 100\n");
    const json light = {{"type", "ies"}, {"file", "disc.ies"}, {"position", {0, 0.05, 0}},
                        {"spectrum", {{"illuminant", "D65"}}}, {"luminous_opening", true}};
    const auto scene = scene_with_light(folder, light);
    const double r = 0.1, h = 0.05;
    // 1/d² varies across the disc: more samples than the point cases for the 1 % standard error check_reading asks.
    check_reading(measure_illuminance_lx(scene->transport_view(), {0, 0, 0}, {0, 1, 0}, test::library().photopic_v(), 40000, 11),
                  2.0 * 100.0 / (r * r) * (1.0 - h / std::sqrt(r * r + h * h)));
    json point = light;
    point["luminous_opening"] = false;
    check_reading(meter(*scene_with_light(folder, point), {0, 0, 0}), 100.0 / (h * h));
    // A file without an opening, and an ellipse, are refused under the key.
    folder.write("ellipse.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 -0.2 -0.4 0\n1 1 0\n0 90\n0\n100 100\n");
    folder.write("point.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n100 100\n");
    json ellipse = light, no_opening = light;
    ellipse["file"] = "ellipse.ies";
    no_opening["file"] = "point.ies";
    CHECK_THROWS_WITH_AS(scene_with_light(folder, ellipse), doctest::Contains("/lights/0/luminous_opening: "), InputError);
    CHECK_THROWS_WITH_AS(scene_with_light(folder, ellipse), doctest::Contains("an ellipse"), InputError);
    CHECK_THROWS_WITH_AS(scene_with_light(folder, no_opening), doctest::Contains("gives no luminous opening"), InputError);
  }
}
