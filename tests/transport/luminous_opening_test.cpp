// Luminous openings of goniometric lights (transport/lights/luminous_opening.h): the shapes LM-63's width, length and
// height describe, points uniform on their surface, the weight whose mean over the surface is 1 in every direction
// (so the far field is the table), and the near field against closed forms: an isotropic disc of intensity I on its
// axis gives E = (2I/R²)(1 − h/√(R² + h²)) (a Lambertian disc of radiance I/(πR²)); an isotropic sphere gives I/d²
// outside it, exactly (a Lambertian sphere's illuminance law). Tolerances: 4.5 standard errors of the estimates.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "light_test_support.h"
#include "spectral/spectra/spectrum.h"
#include "transport/lights/candela_distribution.h"
#include "transport/lights/goniometric_light.h"
#include "transport/lights/luminous_opening.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;

Vec3 random_direction(std::mt19937& rng) {
  const double z = 1.0 - 2.0 * test::uniform01(rng), phi = 2.0 * kPi * test::uniform01(rng);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
}

std::shared_ptr<const CandelaDistribution> isotropic(double candela) {
  return std::make_shared<const CandelaDistribution>(std::vector<double>{0, 180}, std::vector<double>{0, 360},
                                                     std::vector<double>{candela, candela, candela, candela});
}

// E at a receiver facing the light: mean of the light samples' radiance × cos at the receiver.
test::MeanEstimate illuminance(const GoniometricLight& light, Vec3 receiver, Vec3 normal, int n, unsigned seed) {
  std::mt19937 rng(seed);
  const SampledWavelengths lambda = SampledWavelengths::sample_visible(0.4f);
  test::MeanEstimate e;
  for (int i = 0; i < n; ++i) {
    const auto s = light.sample_li({receiver, normal}, lambda, {test::uniform01(rng), test::uniform01(rng)});
    e.add(s ? double(s->radiance[0]) * std::max(0.0f, dot(s->wi, normal)) : 0.0);
  }
  return e;
}

}  // namespace

TEST_CASE("luminous opening: LM-63 width, length and height map to shapes, the others are refused by value") {
  CHECK(luminous_opening_from_lm63(0, 0, 0, 1).opening->is_point());
  const auto rect = luminous_opening_from_lm63(0.2, 0.6, 0, 1).opening;
  REQUIRE(rect);
  CHECK(rect->shape() == LuminousOpening::Shape::rectangle);
  CHECK(rect->area_m2() == doctest::Approx(0.12));
  // Length along x (the C = 0° axis), width along y.
  CHECK(rect->half_extent_m().x == doctest::Approx(0.3));
  CHECK(rect->half_extent_m().y == doctest::Approx(0.1));
  // Feet.
  CHECK(luminous_opening_from_lm63(1, 1, 0, 0.3048).opening->area_m2() == doctest::Approx(0.3048 * 0.3048));
  CHECK(luminous_opening_from_lm63(0.2, 0.6, 0.1, 1).opening->shape() == LuminousOpening::Shape::box);
  CHECK(luminous_opening_from_lm63(-0.1, -0.1, 0, 1).opening->shape() == LuminousOpening::Shape::disc);
  CHECK(luminous_opening_from_lm63(-0.1, -0.1, 0.2, 1).opening->shape() == LuminousOpening::Shape::cylinder);
  CHECK(luminous_opening_from_lm63(-0.1, -0.1, -0.1, 1).opening->shape() == LuminousOpening::Shape::sphere);
  const auto ellipse = luminous_opening_from_lm63(-0.1, -0.3, 0, 1);
  CHECK_FALSE(ellipse.opening);
  CHECK(ellipse.error.find("ellipse") != std::string::npos);
  CHECK_FALSE(luminous_opening_from_lm63(0.1, -0.3, 0.2, 1).opening);
}

TEST_CASE("luminous opening: points lie on the surface, and the weight averages to 1 in every direction") {
  const LuminousOpening shapes[] = {LuminousOpening::rectangle(0.6, 0.2), LuminousOpening::disc(0.3),
                                    LuminousOpening::box(0.6, 0.2, 0.1), LuminousOpening::cylinder(0.2, 0.5),
                                    LuminousOpening::sphere(0.4)};
  std::mt19937 rng(3);
  for (const LuminousOpening& o : shapes) {
    CAPTURE(o.name());
    const Vec3 h = o.half_extent_m();
    for (int i = 0; i < 2000; ++i) {
      const auto p = o.sample({test::uniform01(rng), test::uniform01(rng)});
      REQUIRE(std::fabs(p.position_m.x) <= h.x * (1 + 1e-5f) + 1e-7f);
      REQUIRE(std::fabs(p.position_m.y) <= h.y * (1 + 1e-5f) + 1e-7f);
      REQUIRE(std::fabs(p.position_m.z) <= h.z * (1 + 1e-5f) + 1e-7f);
      REQUIRE(length(p.normal) == doctest::Approx(1.0f).epsilon(1e-5));
      if (o.shape() == LuminousOpening::Shape::sphere) REQUIRE(length(p.position_m) == doctest::Approx(0.2f).epsilon(1e-5));
    }
    // E[w(ω)] over points uniform by area is 1 for any direction (then the far field is the table's).
    for (int k = 0; k < 6; ++k) {
      const Vec3 w = random_direction(rng);
      CAPTURE(w);
      test::MeanEstimate mean;
      for (int i = 0; i < 20000; ++i) {
        const auto p = o.sample({test::uniform01(rng), test::uniform01(rng)});
        mean.add(o.weight(p.normal, w));
      }
      if (mean.standard_error() == 0.0) CHECK(mean.mean() == doctest::Approx(1.0).epsilon(1e-12));
      else CHECK(std::abs(mean.mean() - 1.0) <= 4.5 * mean.standard_error());
    }
  }
  // The box's silhouette is Σ_f A_f max(0, n_f·ω), exactly.
  const LuminousOpening box = LuminousOpening::box(0.6, 0.2, 0.1);
  const Vec3 w = normalize(Vec3{0.3f, -0.5f, 0.8f});
  CHECK(box.projected_area_m2(w) == doctest::Approx(0.2 * 0.1 * 0.3 / length(Vec3{0.3f, -0.5f, 0.8f}) +
                                                    0.6 * 0.1 * 0.5 / length(Vec3{0.3f, -0.5f, 0.8f}) +
                                                    0.6 * 0.2 * 0.8 / length(Vec3{0.3f, -0.5f, 0.8f})).epsilon(1e-6));
}

TEST_CASE("luminous opening: near field of an isotropic disc and sphere against their closed forms") {
  const double candela = 500.0, radius = 0.1;
  const LightSpectrum spectrum(std::make_shared<ConstantSpectrum>(1.0), 1.0);
  GoniometricLight disc_light({0, 3, 0}, {0, -1, 0}, {1, 0, 0}, spectrum, isotropic(candela));
  disc_light.set_opening(LuminousOpening::disc(2 * radius));
  GoniometricLight sphere_light({0, 3, 0}, {0, -1, 0}, {1, 0, 0}, spectrum, isotropic(candela));
  sphere_light.set_opening(LuminousOpening::sphere(2 * radius));
  for (double h : {0.02, 0.1, 0.5, 3.0}) {
    CAPTURE(h);
    // The disc (in the plane y = 3) seen from below on its axis, the receiver facing up.
    const double disc_exact = 2.0 * candela / (radius * radius) * (1.0 - h / std::sqrt(radius * radius + h * h));
    const test::MeanEstimate disc = illuminance(disc_light, {0, float(3 - h), 0}, {0, 1, 0}, 40000, 5);
    CAPTURE(disc.mean());
    CHECK(std::abs(disc.mean() - disc_exact) <= 4.5 * disc.standard_error() + 1e-5 * disc_exact);
    // A point light would give I/h²: the near field differs (by 4x at h = R/5), the far field agrees to 1 %.
    if (h == 0.02) CHECK(disc_exact < 0.3 * candela / (h * h));
    if (h == 3.0) CHECK(disc_exact == doctest::Approx(candela / (h * h)).epsilon(0.01));
    // The sphere from its centre's distance d = R + h, the receiver facing the centre.
    const double d = radius + h;
    const test::MeanEstimate sphere = illuminance(sphere_light, {0, float(3 - d), 0}, {0, 1, 0}, 40000, 7);
    CAPTURE(sphere.mean());
    CHECK(std::abs(sphere.mean() - candela / (d * d)) <= 4.5 * sphere.standard_error());
  }
  // The tree's bounds cover the opening.
  const auto bounds = sphere_light.part_bounds(0);
  REQUIRE(bounds);
  CHECK(bounds->lower_m.x <= -radius * 0.999);
  CHECK(bounds->upper_m.y >= 3 + radius * 0.999);
}
