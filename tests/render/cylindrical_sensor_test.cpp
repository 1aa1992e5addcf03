// Cylindrical and semi-cylindrical illuminance meters (render/sensors/, transport/integrators/meter_receptor.h)
// against their closed forms: a point source of intensity I at distance d and polar angle θ from the cylinder's
// axis gives E_cyl = I sin θ / (π d²) and E_sc = I sin θ (1 + cos α) / (π d²), α the azimuth between the
// semi-cylinder's facing and the source; a uniform radiance L all round gives π L to both (∫ sin θ dω = π²).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <numbers>

#include "input_error_check.h"
#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "render/sensors/sensor_measurement.h"
#include "render/sensors/sensor_outputs.h"
#include "sensor_test_support.h"
#include "test_support.h"
#include "transport/integrators/meter_receptor.h"

using namespace rimu;
using nlohmann::json;

namespace cylindrical_sensor_test {

using rimu::test::kPi;
test::LoadedSensors load(const json& document) { return test::load_sensors(document, "cylinders.json"); }

SensorReadings measure(const test::LoadedSensors& loaded) { return test::measure(loaded, 5); }

json cylinder(const std::string& name, std::vector<double> position, std::vector<double> axis) {
  return {{"name", name}, {"type", "cylindrical"}, {"position", position}, {"axis", axis}};
}
json semi_cylinder(const std::string& name, std::vector<double> position, std::vector<double> axis,
                   std::vector<double> facing) {
  return {{"name", name}, {"type", "semi_cylindrical"}, {"position", position}, {"axis", axis}, {"facing", facing}};
}

TEST_CASE("cylindrical sensors: a point source gives I sin θ / (π d²), and (1 + cos α) times that facing it") {
  const double candela = 1000.0;
  const json lamp = {{"type", "point"}, {"position", {0, 0, 3}}, {"spectrum", {{"blackbody", 2856}}},
                     {"luminous_intensity_cd", candela}};
  // Meters at (x, y, z) with a vertical (+z) axis: the lamp is at d² = x² + y² + (3 − z)², sin θ = √(x² + y²) / d.
  // The semi-cylinders at (2, 0, 1) face the lamp (α = 0), across it (α = 90°, the facing's vertical part is
  // dropped), away from it (α = 180°) and at 60° to it.
  const json meters = json::array({cylinder("c1", {1, 0, 0}, {0, 0, 1}), cylinder("c2", {2, 1, 1}, {0, 0, 1}),
                                   cylinder("c3", {0.5, -0.5, 2.5}, {0, 0, 1}),
                                   // A horizontal axis along x: θ is measured from x, so sin θ = √(y² + Δz²) / d.
                                   cylinder("c4", {2, 1, 1}, {1, 0, 0}),
                                   semi_cylinder("s0", {2, 0, 1}, {0, 0, 1}, {-1, 0, 0}),
                                   semi_cylinder("s90", {2, 0, 1}, {0, 0, 1}, {0, 1, 3}),
                                   semi_cylinder("s180", {2, 0, 1}, {0, 0, 1}, {1, 0, 0}),
                                   semi_cylinder("s60", {2, 0, 1}, {0, 0, 1}, {-0.5, std::sqrt(0.75), 0})});
  const auto scene = load(test::sensor_scene(json::array({lamp}), {{"samples", 256}, {"meters", meters}}));
  const SensorReadings r = measure(scene);
  REQUIRE(r.meters.size() == 8);
  auto e_cyl = [&](double x, double y, double dz) {
    const double d2 = x * x + y * y + dz * dz;
    return candela * std::sqrt(x * x + y * y) / std::sqrt(d2) / (kPi * d2);
  };
  SUBCASE("cylindrical") {
    test::check_sensor_reading(r.meters[0], e_cyl(1, 0, 3));
    test::check_sensor_reading(r.meters[1], e_cyl(2, 1, 2));
    test::check_sensor_reading(r.meters[2], e_cyl(0.5, -0.5, 0.5));
    // Axis x: the roles of x and z swap (the distance is the same, sin θ = √(1 + 4) / 3).
    test::check_sensor_reading(r.meters[3], e_cyl(1, 2, 2));
  }
  SUBCASE("semi-cylindrical") {
    const double e = e_cyl(2, 0, 2);
    test::check_sensor_reading(r.meters[4], 2.0 * e);
    test::check_sensor_reading(r.meters[5], e);
    CHECK(r.meters[6].value == 0.0);
    test::check_sensor_reading(r.meters[7], 1.5 * e);
  }
  SUBCASE("a cylinder right under the lamp, along the light, reads nothing") {
    const auto below = load(test::sensor_scene(json::array({lamp}), {{"samples", 16}, {"meters", {cylinder("c", {0, 0, 0}, {0, 0, 1})}}}));
    // sin θ rounds to at most ~3e-4 in single precision there: 1e-3 of the scale I / (π d²) bounds it.
    CHECK(measure(below).meters[0].value <= 1e-3 * candela / (kPi * 9.0));
  }
}

TEST_CASE("cylindrical sensors: a uniform radiance L all round gives π L whatever the axis and facing") {
  // E = ∫ L w dω over the whole sphere: ∫ sin θ / π dω = π and ∫ ω·f / π dω = 0. The sky is sampled both as a light
  // and by the receptor's uniform directions, so this checks the two techniques' MIS weights sum to one.
  const double luminance_nt = 1000.0;
  const json sky = {{"type", "environment"}, {"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", luminance_nt}};
  const json meters = json::array({cylinder("up", {0, 0, 0}, {0, 0, 1}), cylinder("tilted", {1, 2, 3}, {1, 1, 0.3}),
                                   semi_cylinder("semi", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}),
                                   semi_cylinder("semi_tilted", {0, 0, 0}, {0, 1, 1}, {1, 0, 0})});
  const auto scene = load(test::sensor_scene(json::array({sky}), {{"samples", 1024}, {"meters", meters}}));
  const SensorReadings r = measure(scene);
  for (size_t k = 0; k < r.meters.size(); ++k) {
    CAPTURE(k);
    test::check_sensor_reading(r.meters[k], kPi * luminance_nt);
  }
  const std::string csv = sensor_csv(scene.sensors, r);
  CHECK(csv.find("\nup,cylindrical_illuminance,,,0,0,0,0,0,1,") != std::string::npos);
  CHECK(csv.find("\nsemi,semi_cylindrical_illuminance,,,0,0,0,0,0,1,") != std::string::npos);
  const json doc = sensor_json(scene.sensors, r, 1024);
  CHECK(doc["meters"][0]["quantity"] == "cylindrical_illuminance");
  CHECK(doc["meters"][0]["axis"] == json::array({0.0, 0.0, 1.0}));
  CHECK(doc["meters"][3]["facing"][0].get<double>() == doctest::Approx(1.0));
}

TEST_CASE("cylindrical sensors: the receptors' directions follow their densities (chi-square)") {
  // 16 bins of cos θ (along the axis) × 32 of α (around it, from the facing): each bin's expected count is N times
  // the density's integral over it, Δ(cos θ) ∫ p dα with p = 1/4π (cylinder) or (1 + cos α)/4π (semi-cylinder).
  const Vec3 axis = normalize(Vec3{0.3f, -0.2f, 1.0f});
  const Vec3 facing = normalize(cross(axis, Vec3{1.0f, 0.0f, 0.0f}));
  const Vec3 side = cross(axis, facing);
  for (const MeterReceptor::Shape shape : {MeterReceptor::Shape::cylinder, MeterReceptor::Shape::semi_cylinder}) {
    const MeterReceptor receptor{shape, axis, facing};
    const bool semi = shape == MeterReceptor::Shape::semi_cylinder;
    constexpr int kZ = 16, kAlpha = 32, kSamples = 400000;
    std::vector<double> counts(kZ * kAlpha, 0.0);
    uint64_t state = 12345;
    auto next = [&state] {  // a 64-bit LCG's top 24 bits: enough for a test of the warp
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return float(state >> 40) * 0x1p-24f;
    };
    double max_pdf_error = 0.0;
    for (int k = 0; k < kSamples; ++k) {
      const float u0 = next(), u1 = next();
      const Vec3 w = receptor.sample_direction({u0, u1});
      const double z = dot(w, axis), alpha = std::atan2(dot(w, side), dot(w, facing));
      const int iz = std::clamp(int((z + 1.0) / 2.0 * kZ), 0, kZ - 1);
      const int ia = std::clamp(int((alpha + kPi) / (2.0 * kPi) * kAlpha), 0, kAlpha - 1);
      counts[size_t(iz * kAlpha + ia)] += 1.0;
      const double expected_pdf = (semi ? 1.0 + std::cos(alpha) : 1.0) / (4.0 * kPi);
      if (std::sqrt(std::max(0.0, 1.0 - z * z)) > 1e-3)
        max_pdf_error = std::max(max_pdf_error, std::abs(receptor.direction_pdf(w) - expected_pdf));
    }
    double chi2 = 0.0;
    for (int iz = 0; iz < kZ; ++iz)
      for (int ia = 0; ia < kAlpha; ++ia) {
        const double a0 = -kPi + 2.0 * kPi * ia / kAlpha, a1 = a0 + 2.0 * kPi / kAlpha;
        const double alpha_integral = semi ? (a1 + std::sin(a1)) - (a0 + std::sin(a0)) : a1 - a0;
        const double expected = kSamples * (2.0 / kZ) * alpha_integral / (4.0 * kPi);
        const double d = counts[size_t(iz * kAlpha + ia)] - expected;
        chi2 += d * d / expected;
      }
    CAPTURE(semi);
    // 511 degrees of freedom: mean 511, standard deviation 32; 650 is 4.3 of them (p ≈ 1e-5).
    CHECK(chi2 < 650.0);
    CHECK(max_pdf_error < 1e-4);
  }
}

TEST_CASE("cylindrical sensors: bad meters are refused by key") {
  const json lamp = json::array({{{"type", "point"}, {"position", {0, 0, 2}}, {"spectrum", {{"blackbody", 3000}}},
                                  {"luminous_intensity_cd", 100}}});
  auto fails = [&](json meter, std::initializer_list<std::string> fragments) {
    test::input_error([&] { load(test::sensor_scene(lamp, {{"meters", {std::move(meter)}}})); }, fragments);
  };
  fails({{"type", "cylindrical"}, {"position", {0, 0, 0}}}, {"/sensors/meters/0", "axis"});
  fails({{"type", "cylindrical"}, {"position", {0, 0, 0}}, {"axis", {0, 0, 1}}, {"normal", {0, 0, 1}}},
        {"/sensors/meters/0", "normal"});
  fails({{"type", "cylindrical"}, {"position", {0, 0, 0}}, {"axis", {0, 0, 0}}}, {"/sensors/meters/0/axis", "non-zero"});
  fails({{"type", "semi_cylindrical"}, {"position", {0, 0, 0}}, {"axis", {0, 0, 1}}}, {"/sensors/meters/0", "facing"});
  fails({{"type", "semi_cylindrical"}, {"position", {0, 0, 0}}, {"axis", {0, 0, 1}}, {"facing", {0, 0, -2}}},
        {"/sensors/meters/0/facing", "across its axis"});
  fails({{"type", "cylindrical"}, {"position", {0, 0, 0}}, {"axis", {0, 0, 1}}, {"facing", {1, 0, 0}}},
        {"/sensors/meters/0", "facing"});
}

}  // namespace cylindrical_sensor_test
