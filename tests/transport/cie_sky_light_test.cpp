// The CIE sky light (transport/lights/sky/cie_sky_light.h): its sampling density against sample frequencies
// (chi-square), its illuminance by light sampling against quadrature of its own radiance, the calibration
// integrals (exact for the uniform sky, converged for the others), and nothing below the horizon.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numeric>
#include <numbers>
#include <random>
#include <vector>

#include "light_test_support.h"
#include "square_chi_square.h"
#include "transport/lights/sky/cie_sky_light.h"
#include "test_support.h"

using namespace rimu;

namespace {
using rimu::test::kLambda;
using rimu::test::kPi;

/// The sun at elevation `elevation_deg` and azimuth `azimuth_deg` about `up` = +y (azimuth 0 along +x).
Vec3 sun_towards(double elevation_deg, double azimuth_deg) {
  const double h = elevation_deg * kPi / 180, a = azimuth_deg * kPi / 180;
  return normalize(Vec3{float(std::cos(h) * std::cos(a)), float(std::sin(h)), float(std::cos(h) * std::sin(a))});
}

CieSkyLight sky(int type, Vec3 sun, double zenith_radiance = 1.0) {
  return CieSkyLight(type, {0, 1, 0}, sun, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), zenith_radiance));
}

/// ∫ L max(0, n·ω) dω over the upper hemisphere by midpoints in (φ, cos θ) of the light's own frame.
double irradiance_quadrature(const CieSkyLight& light, Vec3 normal, int nu, int nv) {
  double sum = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const Vec3 d = light.uv_to_direction({(i + 0.5f) / nu, (j + 0.5f) / nv});
      sum += light.radiance_escaped(d, kLambda)[1] * std::max(0.0f, dot(d, normal));
    }
  return sum * 2 * kPi / (double(nu) * nv);
}

test::MeanEstimate irradiance_estimate(const CieSkyLight& light, Vec3 normal, int n, unsigned seed) {
  std::mt19937 rng(seed);
  test::MeanEstimate e;
  const LightReference ref{{1, 2, 3}, normal};
  for (int i = 0; i < n; ++i) {
    const auto s = light.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    if (!s) {
      e.add(0.0);
      continue;
    }
    REQUIRE(s->pdf_solid_angle == light.pdf_li(ref, s->wi));
    REQUIRE(std::isinf(s->distance));
    e.add(s->radiance[1] * std::max(0.0f, dot(s->wi, normal)) / s->pdf_solid_angle);
  }
  return e;
}
}  // namespace

TEST_CASE("CIE sky light: sampling matches pdf_li, by chi-square over the hemisphere") {
  // 64 × 32 bins in (φ/2π, 1 − cos θ); expected counts N ∫_bin pdf_li dω with dω = 2π du dv, by 4 × 4 midpoints.
  for (int type : {1, 8, 12, 15}) {
    CAPTURE(type);
    const CieSkyLight light = sky(type, sun_towards(type == 15 ? 8.0 : 35.0, 70.0));
    const int nu = 64, nv = 32, sub = 4, n = 200000;
    std::vector<double> observed(nu * nv, 0.0);
    const std::vector<double> expected = test::square_expected_counts(
        [&](Vec2 uv) { return light.pdf_li({}, light.uv_to_direction(uv)) * 2 * kPi; }, nu, nv, sub, n);
    CHECK(std::accumulate(expected.begin(), expected.end(), 0.0) / n == doctest::Approx(1.0).epsilon(1e-4));
    std::mt19937 rng(41);
    for (int s = 0; s < n; ++s) {
      const auto ls = light.sample_li({}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
      if (!ls) continue;  // a direction rounded onto the horizon (measure zero)
      const Vec2 uv = light.direction_to_uv(ls->wi);
      observed[test::square_cell(uv, nu, nv)] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(chi.statistic);
    CHECK(chi.p_value > test::kChiSquareAlpha);
  }
}

TEST_CASE("CIE sky light: illuminance by light sampling equals quadrature of its radiance and its integrals") {
  for (int type : {1, 5, 12, 14}) {
    CAPTURE(type);
    const CieSkyLight light = sky(type, sun_towards(40.0, 200.0), 2.5);
    // Horizontal: E = L_z ∫ L/L_z cos θ dω, the calibration integral.
    const auto horizontal = irradiance_estimate(light, {0, 1, 0}, 40000, 43);
    CAPTURE(horizontal.mean());
    CAPTURE(horizontal.standard_error());
    const double expected = 2.5 * light.integrals().cosine_weighted_sr;
    CHECK(horizontal.standard_error() < 0.01 * expected);
    CHECK(std::abs(horizontal.mean() - expected) <= test::kMonteCarloSigmas * horizontal.standard_error());
    // A vertical plane facing the sun's side and one facing away (the quadrature's midpoint error is ~1e-4).
    for (Vec3 normal : {Vec3{-0.5f, 0, -0.866f}, normalize(Vec3{1, 0.2f, 0})}) {
      const double exact = irradiance_quadrature(light, normal, 1024, 512);
      const auto e = irradiance_estimate(light, normal, 40000, 44);
      CAPTURE(exact);
      CAPTURE(e.mean());
      CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + 1e-3 * exact);
    }
  }
}

TEST_CASE("CIE sky integrals: the uniform sky exactly, the others converged to 1e-5") {
  // Type 5 is uniform: ∫ cos θ dω = π and ∫ dω = 2π over the hemisphere (the midpoint rule is exact for μ).
  const auto uniform = integrate_cie_sky(cie_sky_parameters(5), {0.0, 0.5, std::sqrt(0.75)});
  CHECK(uniform.cosine_weighted_sr == doctest::Approx(kPi).epsilon(1e-12));
  CHECK(uniform.solid_angle_sr == doctest::Approx(2 * kPi).epsilon(1e-12));
  // Type 1 depends on height only: 2π ∫ φ(μ)/φ(1) μ dμ by a 1-D midpoint rule on 10⁶ points.
  const CieSkyParameters& overcast = cie_sky_parameters(1);
  double radial = 0;
  const int n = 1000000;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    radial += cie_gradation(overcast, mu) / cie_gradation(overcast, 1.0) * mu;
  }
  CHECK(integrate_cie_sky(overcast, {0, 0, 1}).cosine_weighted_sr == doctest::Approx(2 * kPi * radial / n).epsilon(1e-6));
  // The clear and turbid skies, whose circumsolar peak is a cusp, against a grid of twice the resolution.
  for (int type : {12, 15})
    for (double elevation_deg : {5.0, 30.0, 75.0}) {
      CAPTURE(type);
      CAPTURE(elevation_deg);
      const double h = elevation_deg * kPi / 180;
      const std::array<double, 3> sun{std::cos(h), 0.0, std::sin(h)};
      const auto coarse = integrate_cie_sky(cie_sky_parameters(type), sun);
      const auto fine = integrate_cie_sky(cie_sky_parameters(type), sun, 2048, 1024);
      CHECK(coarse.cosine_weighted_sr == doctest::Approx(fine.cosine_weighted_sr).epsilon(1e-5));
      CHECK(coarse.solid_angle_sr == doctest::Approx(fine.solid_angle_sr).epsilon(1e-5));
    }
}

TEST_CASE("CIE sky light: nothing below the horizon, power, spectrum") {
  const CieSkyLight light = sky(12, sun_towards(30.0, 0.0), 2.0);
  const Vec3 below = normalize(Vec3{0.3f, -0.2f, 0.5f});
  CHECK(light.radiance_escaped(below, kLambda)[0] == 0.0f);
  CHECK(light.pdf_li({}, below) == 0.0f);
  CHECK(light.radiance_escaped({0, 1, 0}, kLambda)[0] == doctest::Approx(2.0f));  // the zenith is L_z
  CHECK(light.is_infinite());
  CHECK_FALSE(light.is_delta());
  REQUIRE(light.emitted_spectrum());
  CHECK(light.total_power_w(3.0) == doctest::Approx(kPi * 9.0 * 2.0 * 470.0 * light.integrals().solid_angle_sr).epsilon(1e-9));
  // Brightest near the sun.
  CHECK(light.relative_luminance(sun_towards(31.0, 0.0)) > light.relative_luminance(sun_towards(31.0, 120.0)));
}

TEST_CASE("CIE sky light with a portal: samples only through it, pdf_li agrees, irradiance equals quadrature") {
  // A 1 m × 2 m horizontal skylight 2 m above a point (y up) and a clear sky with the sun at 40°: light sampling
  // through the portal estimates ∫_portal L cos θ dω, which a midpoint rule over the rectangle gives independently
  // (dω = cos θ_o dA / r²). Tolerance 4.5 standard errors.
  CieSkyLight light = sky(12, sun_towards(40.0, 30.0), 1.5);
  const auto portal = PortalRectangle::from_corners({-0.5f, 2, -1}, {0.5f, 2, -1}, {0.5f, 2, 1}, {-0.5f, 2, 1});
  REQUIRE(portal);
  light.set_portals(PortalSet({*portal}));
  const Vec3 normal{0, 1, 0};
  const LightReference ref{{0.2f, 0, 0.3f}, normal};
  std::mt19937 rng(11);
  test::MeanEstimate estimate;
  for (int i = 0; i < 20000; ++i) {
    const auto s = light.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(s);  // every direction through a skylight is above the horizon
    REQUIRE(passes_through(*portal, ref.position, s->wi));
    REQUIRE(s->pdf_solid_angle == light.pdf_li(ref, s->wi));
    estimate.add(s->radiance[1] * std::max(0.0f, dot(s->wi, normal)) / s->pdf_solid_angle);
  }
  // A direction that misses the portal has density 0 (it is reached by BSDF sampling only).
  CHECK(light.pdf_li(ref, normalize(Vec3{1, 0.2f, 0})) == 0.0f);
  double quadrature = 0.0;
  const int n = 400;
  for (int j = 0; j < 2 * n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 q{-0.5f + (i + 0.5f) / n, 2.0f, -1.0f + (j + 0.5f) / n};
      const Vec3 r = q - ref.position;
      const double r2 = dot(r, r);
      const Vec3 w = normalize(r);
      quadrature += light.radiance_escaped(w, kLambda)[1] * w.y * w.y / r2;
    }
  quadrature *= 2.0 / (double(n) * 2 * n);
  CAPTURE(estimate.mean());
  CAPTURE(estimate.standard_error());
  CHECK(std::abs(estimate.mean() - quadrature) <= 4.5 * estimate.standard_error());
  CHECK(estimate.standard_error() < 0.01 * quadrature);

  // For the light tree: a leaf on the portal, two-sided, of radiance ∫S dλ ∫ L/L_z cos θ dω / π, whose power is
  // that radiance times π A.
  const auto bounds = light.part_bounds(0);
  REQUIRE(bounds);
  CHECK(bounds->two_sided);
  const double radiance = 1.5 * 470.0 * light.integrals().cosine_weighted_sr / kPi;
  CHECK(light.total_power_w(100.0) == doctest::Approx(kPi * 2.0 * radiance).epsilon(1e-6));
  // Without portals again: no bounds, the whole sky's power.
  light.set_portals({});
  CHECK_FALSE(light.part_bounds(0));
}
