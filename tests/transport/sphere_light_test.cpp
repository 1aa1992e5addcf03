// Analytic sphere lights: cone sampling against its pdf by chi-square (near, middle and far), pdf_li equal to the
// sample's density, irradiance against π L sin²θmax cos β, the inside of a two-sided sphere (E = π L), sides, power,
// and light-tree bounds that never cull a point the sphere can light.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "light_test_support.h"
#include "transport/geometry/frame.h"
#include "transport/lights/light_bounds.h"
#include "transport/lights/sphere_light.h"
#include "test_support.h"

using namespace rimu;

namespace {
using rimu::test::kLambda;
using rimu::test::kPi;
LightSpectrum constant(double value) { return LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), value); }

/// Monte Carlo irradiance ∫ L cos θ dω at `ref` by light sampling (samples below the tangent plane count 0).
test::MeanEstimate irradiance_estimate(const SphereLight& light, const LightReference& ref, int n, unsigned seed) {
  return test::light_sampling_irradiance(light, ref, kLambda, n, seed);
}
}  // namespace

TEST_CASE("sphere light cone sampling is uniform in the subtended cone, and pdf_li equals the sample's density") {
  // Uniform in the cone ⇔ 1 − cos θ uniform on [0, 1 − cos θmax] and φ uniform: 10 × 12 equal-solid-angle cells
  // get equal expected counts. d/r = 1.05 (a 72° cone), 3 and 1000 (1 − cos θmax = 5e-7).
  const Vec3 centre{0.3f, -1.2f, 2.0f};
  const float radius = 0.25f;
  const Vec3 towards = normalize(Vec3{0.4f, 0.7f, -0.2f});
  for (double d_over_r : {1.05, 3.0, 1000.0}) {
    CAPTURE(d_over_r);
    const SphereLight light(centre, radius, constant(2.0), false);
    const Vec3 p = centre + towards * float(d_over_r * radius);
    const LightReference ref{p, {0, 0, 0}};
    const Vec3 axis = normalize(centre - p);
    const Frame f = Frame::from_normal(axis);
    const double sin2_max = 1.0 / (d_over_r * d_over_r);
    const double omc_max = sin2_max / (1.0 + std::sqrt(1.0 - sin2_max));
    const int rings = 10, sectors = 12, n = 120000;
    std::vector<double> observed(rings * sectors, 0.0), expected(rings * sectors, double(n) / (rings * sectors));
    std::mt19937 rng(31);
    for (int i = 0; i < n; ++i) {
      const auto s = light.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
      REQUIRE(s);
      CHECK(s->pdf_solid_angle == doctest::Approx(1.0 / (2.0 * kPi * omc_max)).epsilon(1e-5));
      REQUIRE(light.pdf_li(ref, s->wi) == doctest::Approx(s->pdf_solid_angle).epsilon(1e-6));
      // The sampled point is on the sphere, at the sample's distance along wi, facing the reference.
      const Vec3 y = p + s->wi * s->distance;
      CHECK(length(y - centre) == doctest::Approx(radius).epsilon(2e-4 * d_over_r));
      CHECK(dot(s->normal, -s->wi) >= -1e-3f);
      const Vec3 local = f.to_local(s->wi);
      const double omc = 0.5 * double(length_squared(s->wi - axis));
      double phi = std::atan2(local.y, local.x);
      if (phi < 0) phi += 2 * kPi;
      const int ring = std::min(rings - 1, int(omc / omc_max * rings));
      const int sector = std::min(sectors - 1, int(phi / (2 * kPi) * sectors));
      observed[size_t(ring * sectors + sector)] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(chi.statistic);
    CHECK(chi.p_value > test::kChiSquareAlpha);
    // Outside the cone nothing is sampled or seen: the direction at 1.01 θmax, and away from the sphere.
    const double theta_beyond = 1.01 * std::asin(std::sqrt(sin2_max));
    const Vec3 beyond = normalize(f.to_world({float(std::sin(theta_beyond)), 0.0f, float(std::cos(theta_beyond))}));
    CHECK(light.pdf_li(ref, beyond) == 0.0f);
    CHECK(light.pdf_li(ref, -axis) == 0.0f);
  }
}

TEST_CASE("sphere light irradiance is pi L sin^2(theta_max) cos(beta) wherever the sphere is above the horizon") {
  // A sphere wholly above a receiver's tangent plane sends E = L ∫cone cos dω = π L sin²θmax cos β (β between the
  // normal and the direction to the centre): head-on at d = 1.02 r, 1.05 r, 3 r and 1e4 r, and grazing (β + θmax
  // = 89°), by light sampling.
  const Vec3 centre{1.0f, 2.0f, -0.5f};
  const float radius = 0.1f;
  const double radiance = 3.0;
  const SphereLight light(centre, radius, constant(radiance), false);
  struct Case {
    double d_over_r, beta_deg;
  };
  for (const Case c : {Case{1.02, 0.0}, Case{1.05, 0.0}, Case{1.05, 17.0}, Case{3.0, 0.0}, Case{3.0, 89.0 - 19.47},
                       Case{1e4, 0.0}, Case{1e4, 88.9}}) {
    CAPTURE(c.d_over_r);
    CAPTURE(c.beta_deg);
    const Vec3 to_p = normalize(Vec3{0.2f, -1.0f, 0.3f});
    const Vec3 p = centre + to_p * float(c.d_over_r * radius);
    // The normal at β from −to_p (towards the centre), turned in an arbitrary plane.
    const Frame f = Frame::from_normal(-to_p);
    const double beta = c.beta_deg * kPi / 180;
    const Vec3 normal = normalize(f.to_world({float(std::sin(beta)), 0.0f, float(std::cos(beta))}));
    const auto e = irradiance_estimate(light, {p, normal}, 40000, 7);
    const double exact = kPi * radiance * std::cos(beta) / (c.d_over_r * c.d_over_r);
    CAPTURE(e.mean());
    CAPTURE(e.standard_error());
    CAPTURE(exact);
    // + 1e-5 relative: float rounding of L cos θ / p, whose spread is tiny for small cones.
    CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + 1e-5 * exact);
  }
}

TEST_CASE("sphere light inside: a two-sided sphere gives pi L from every direction, a one-sided one nothing") {
  const Vec3 centre{-2.0f, 0.5f, 1.0f};
  const float radius = 0.5f;
  const double radiance = 1.5;
  const SphereLight two_sided(centre, radius, constant(radiance), true);
  const SphereLight one_sided(centre, radius, constant(radiance), false);
  std::mt19937 rng(5);
  for (const float where : {0.0f, 0.5f, 0.95f}) {
    CAPTURE(where);
    const Vec3 p = centre + normalize(Vec3{1.0f, 2.0f, -1.0f}) * (where * radius);
    for (const Vec3 normal : {Vec3{0, 1, 0}, normalize(Vec3{1, 1, 1}), normalize(Vec3{-1, 2, -1})}) {
      CAPTURE(normal);
      const LightReference ref{p, normal};
      // The inside of a sphere of uniform radiance is a furnace: E = π L for every normal.
      const auto e = irradiance_estimate(two_sided, ref, 40000, 9);
      CAPTURE(e.mean());
      CAPTURE(e.standard_error());
      CHECK(std::abs(e.mean() - kPi * radiance) <= test::kMonteCarloSigmas * e.standard_error() + 1e-5 * kPi * radiance);
      for (int i = 0; i < 200; ++i) {
        const Vec2 u{test::uniform01(rng), test::uniform01(rng)};
        const auto s = two_sided.sample_li(ref, kLambda, u);
        REQUIRE(s);
        CHECK(two_sided.pdf_li(ref, s->wi) == doctest::Approx(s->pdf_solid_angle).epsilon(1e-4));
        CHECK_FALSE(one_sided.sample_li(ref, kLambda, u));
        CHECK(one_sided.pdf_li(ref, s->wi) == 0.0f);
      }
    }
  }
}

TEST_CASE("sphere light inside: area sampling is distributed as pdf_li says (chi-square over directions)") {
  // 8 × 16 cells in (z, φ) of wi about a fixed frame; each cell's expected count is n ∫cell pdf_li dω by the
  // midpoint rule on a 24 × 24 grid per cell (the density is smooth inside the sphere: the quadrature error is far
  // below the counts' noise).
  const Vec3 centre{0.0f, 0.0f, 0.0f};
  const float radius = 1.0f;
  const SphereLight light(centre, radius, constant(1.0), true);
  const LightReference ref{{0.0f, 0.3f, 0.6f}, {0, 0, 0}};
  const int zs = 8, phis = 16, sub = 24, n = 100000;
  std::vector<double> observed(size_t(zs * phis), 0.0), expected(size_t(zs * phis), 0.0);
  for (int i = 0; i < zs; ++i)
    for (int j = 0; j < phis; ++j) {
      double integral = 0.0;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double z = -1.0 + 2.0 * (i + (a + 0.5) / sub) / zs, phi = 2 * kPi * (j + (b + 0.5) / sub) / phis;
          const double s = std::sqrt(1.0 - z * z);
          integral += light.pdf_li(ref, Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)));
        }
      expected[size_t(i * phis + j)] = n * integral * (4.0 * kPi / (zs * phis)) / (sub * sub);
    }
  std::mt19937 rng(3);
  for (int k = 0; k < n; ++k) {
    const auto s = light.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(s);
    double phi = std::atan2(s->wi.y, s->wi.x);
    if (phi < 0) phi += 2 * kPi;
    const int i = std::clamp(int((s->wi.z + 1.0f) * 0.5f * zs), 0, zs - 1);
    const int j = std::min(phis - 1, int(phi / (2 * kPi) * phis));
    observed[size_t(i * phis + j)] += 1;
  }
  double total_expected = 0;
  for (double x : expected) total_expected += x;
  CHECK(total_expected == doctest::Approx(n).epsilon(2e-3));  // pdf_li integrates to 1 over the sphere of directions
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);
}

TEST_CASE("sphere light emits from its outside (both sides if asked) and has the Lambertian power") {
  const SphereLight light({0, 0, 0}, 2.0f, constant(0.5), false);
  const SphereLight both({0, 0, 0}, 2.0f, constant(0.5), true);
  SurfaceHit hit;
  hit.position = {0, 2, 0};
  hit.geometric_normal = {0, 1, 0};
  CHECK(light.radiance(hit, {0, 1, 0}, kLambda)[0] == doctest::Approx(0.5));
  CHECK(light.radiance(hit, {0, -1, 0}, kLambda)[0] == 0.0f);
  CHECK(both.radiance(hit, {0, -1, 0}, kLambda)[0] == doctest::Approx(0.5));
  // Φ = π A ∫L dλ per side, A = 4π r², ∫ over 360-830 nm of a constant 0.5: 235.
  CHECK(light.total_power_w(1.0) == doctest::Approx(kPi * 4 * kPi * 4.0 * 235.0).epsilon(1e-9));
  CHECK(both.total_power_w(1.0) == doctest::Approx(2 * light.total_power_w(1.0)).epsilon(1e-12));
  CHECK(light.part_count() == 1);
}

TEST_CASE("sphere light bounds: the box holds the sphere and every point the sphere can light scores > 0") {
  // A point p with normal n receives light from the sphere iff some surface point y has n·(y − p) > 0, i.e.
  // n·(c − p) + r > 0 (and, one-sided, p is outside). The tree's importance must then be > 0 (light_bounds.h).
  const Vec3 centre{3.0f, -1.0f, 0.5f};
  const float radius = 0.02f;
  const SphereLight light(centre, radius, constant(1.0), false);
  const auto bounds = light.part_bounds(0);
  REQUIRE(bounds);
  CHECK(bounds->intensity_w_sr == doctest::Approx(kPi * radius * radius * 470.0).epsilon(1e-5));
  for (int axis = 0; axis < 3; ++axis) {
    CHECK(bounds->lower_m[axis] <= centre[axis] - radius);
    CHECK(bounds->upper_m[axis] >= centre[axis] + radius);
  }
  CHECK_FALSE(light.part_bounds(1));
  std::mt19937 rng(13);
  int lit = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 dir = normalize(Vec3{test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f});
    const float distance = radius * (1.0f + 200.0f * test::uniform01(rng) * test::uniform01(rng));
    const Vec3 p = centre + dir * distance;
    const Vec3 n = normalize(Vec3{test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f});
    if (!(dot(n, centre - p) + radius > 1e-6f * distance)) continue;
    ++lit;
    CAPTURE(p);
    CAPTURE(n);
    CHECK(light_importance(*bounds, p, n) > 0.0f);
    CHECK(light_importance(*bounds, p, Vec3{}) > 0.0f);
  }
  CHECK(lit > 5000);
}
