// Distant lights: E cos θ on a tilted plane (delta and sun-sized disc), the cone's sampling against its pdf, and
// the power through the scene's disc.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "light_test_support.h"
#include "transport/lights/distant_light.h"
#include "transport/geometry/frame.h"
#include "test_support.h"

using namespace rimu;

namespace {
using rimu::test::kLambda;
LightSpectrum constant(double value) { return LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), value); }
constexpr double kSunDiameterDeg = 0.53;
}  // namespace

TEST_CASE("delta distant light gives E cos theta on a tilted plane") {
  const double irradiance = 100.0;
  const DistantLight sun({0, 0, 1}, constant(irradiance));
  CHECK(sun.is_delta());
  for (double tilt_deg : {0.0, 30.0, 60.0, 89.0}) {
    CAPTURE(tilt_deg);
    const double t = tilt_deg * std::numbers::pi / 180;
    const LightReference ref{{5, -3, 2}, {float(std::sin(t)), 0.0f, float(std::cos(t))}};
    const auto s = sun.sample_li(ref, kLambda, {0.2f, 0.9f});
    REQUIRE(s);
    CHECK(s->is_delta);
    CHECK(std::isinf(s->distance));
    CHECK(s->radiance[1] * dot(s->wi, ref.normal) / s->pdf_solid_angle ==
          doctest::Approx(irradiance * std::cos(t)).epsilon(1e-6));
  }
  CHECK(sun.pdf_li({}, {0, 0, 1}) == 0.0f);
  CHECK(sun.radiance_escaped({0, 0, 1}, kLambda)[0] == 0.0f);
}

TEST_CASE("sun disc radiance is E over pi sin squared alpha and gives E cos theta") {
  // L = E/(π sin²α); a plane tilted by θ with the whole cone above its horizon (θ + α < 90°) receives E cos θ
  // exactly, so the Monte Carlo estimate must agree within kMonteCarloSigmas standard errors. The 0.53° sun cannot
  // tell E/(π sin²α) from E/Ω (they differ by the mean cosine, 1 − 5e-6), so a 30° disc (mean cosine 0.983) is
  // tested too.
  const double irradiance = 1000.0;
  const Vec3 axis = normalize({1, 1, 1});
  for (double diameter : {kSunDiameterDeg, 30.0}) {
    CAPTURE(diameter);
    const DistantLight sun(axis, constant(irradiance), diameter);
    CHECK_FALSE(sun.is_delta());
    const double alpha = 0.5 * diameter * std::numbers::pi / 180;
    CHECK(sun.radiance_per_irradiance() ==
          doctest::Approx(1.0 / (std::numbers::pi * std::sin(alpha) * std::sin(alpha))).epsilon(1e-12));
    CHECK(sun.cone_solid_angle_sr() == doctest::Approx(2 * std::numbers::pi * (1 - std::cos(alpha))).epsilon(1e-9));
    for (double tilt_deg : {0.0, 45.0, 70.0}) {
      CAPTURE(tilt_deg);
      const Frame f = Frame::from_normal(axis);
      const double t = tilt_deg * std::numbers::pi / 180;
      const Vec3 normal = normalize(f.to_world({float(std::sin(t)), 0.0f, float(std::cos(t))}));
      const LightReference ref{{0, 0, 0}, normal};
      std::mt19937 rng(10);
      test::MeanEstimate e;
      for (int i = 0; i < 20000; ++i) {
        const auto s = sun.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
        REQUIRE(s);
        CHECK_FALSE(s->is_delta);
        e.add(s->radiance[0] * std::max(0.0f, dot(s->wi, normal)) / s->pdf_solid_angle);
      }
      const double exact = irradiance * std::cos(t);
      CAPTURE(e.mean());
      CAPTURE(e.standard_error());
      // + 1e-5 relative: float rounding of L·cos/pdf, whose spread is otherwise ~0 at normal incidence.
      CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + 1e-5 * exact);
    }
  }
}

TEST_CASE("sun cone sampling is uniform in solid angle and matches pdf_li") {
  // Uniform in the cone ⇔ 1 − cos θ uniform on [0, 1 − cos α] and φ uniform: 10 × 12 equal-solid-angle cells
  // get equal expected counts. pdf_li must be 1/Ω for each sample (and 0 outside the cone).
  const Vec3 axis = normalize({0.3f, -0.2f, 1.0f});
  for (double diameter : {kSunDiameterDeg, 30.0}) {
    CAPTURE(diameter);
    const DistantLight sun(axis, constant(1.0), diameter);
    const Frame f = Frame::from_normal(axis);
    const double omc_max = 1.0 - std::cos(0.5 * diameter * std::numbers::pi / 180);
    const int rings = 10, sectors = 12, n = 120000;
    std::vector<double> observed(rings * sectors, 0.0), expected(rings * sectors, double(n) / (rings * sectors));
    std::mt19937 rng(11);
    for (int i = 0; i < n; ++i) {
      // u.x < 0.999: the outermost 0.1 % of the cone's 1 − cos θ, where float rounding could put a sample a few ulps
      // outside the cone test, is left out of the pdf comparison (expected counts are scaled to match).
      const Vec2 u{0.999f * test::uniform01(rng), test::uniform01(rng)};
      const auto s = sun.sample_li({}, kLambda, u);
      REQUIRE(s);
      REQUIRE(sun.pdf_li({}, s->wi) == doctest::Approx(s->pdf_solid_angle).epsilon(1e-6));
      CHECK(s->pdf_solid_angle == doctest::Approx(1.0 / sun.cone_solid_angle_sr()).epsilon(1e-5));
      const Vec3 local = f.to_local(s->wi);
      const double omc = 0.5 * length_squared(s->wi - axis);
      double phi = std::atan2(local.y, local.x);
      if (phi < 0) phi += 2 * std::numbers::pi;
      const int ring = std::min(rings - 1, int(omc / (0.999 * omc_max) * rings));
      const int sector = std::min(sectors - 1, int(phi / (2 * std::numbers::pi) * sectors));
      observed[ring * sectors + sector] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(chi.statistic);
    CHECK(chi.p_value > test::kChiSquareAlpha);
    // Just outside the cone nothing is seen or sampled.
    const float outside = float(2.0 * std::acos(1.0 - omc_max));
    const Vec3 beyond = normalize(f.to_world({std::sin(outside), 0.0f, std::cos(outside)}));
    CHECK(sun.pdf_li({}, beyond) == 0.0f);
    CHECK(sun.radiance_escaped(beyond, kLambda)[0] == 0.0f);
    CHECK(sun.radiance_escaped(axis, kLambda)[0] == doctest::Approx(sun.radiance_per_irradiance()).epsilon(1e-6));
  }
}

TEST_CASE("distant light power crosses a disc of the scene radius") {
  const DistantLight sun({0, 1, 0}, constant(2.0), kSunDiameterDeg);
  CHECK(sun.total_power_w(10.0) == doctest::Approx(std::numbers::pi * 100.0 * 2.0 * 470.0).epsilon(1e-12));
  CHECK(sun.is_infinite());
}
