// Point and spot lights: inverse-square irradiance, the smoothstep cone, their radiant power, and hard cases.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "grey_environment_image.h"
#include "transport/lights/point_light.h"
#include "transport/lights/projection_light.h"
#include "transport/lights/spot_light.h"
#include "test_support.h"

using namespace rimu;

namespace {
using rimu::test::kLambda;
LightSpectrum constant(double value) { return LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), value); }
}  // namespace

TEST_CASE("point light irradiance on a facing patch is I over d squared") {
  // A delta light: the single "sample" is exact, E = I cos θ / d² with cos θ = 1. Float rounding only.
  const double intensity = 2.5;
  for (double d : {1e-4, 0.3, 2.0, 1e5}) {
    CAPTURE(d);
    const PointLight light({0.0f, 0.0f, float(d)}, constant(intensity));
    const LightReference ref{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
    const auto s = light.sample_li(ref, kLambda, {0.3f, 0.7f});
    REQUIRE(s);
    CHECK(s->is_delta);
    CHECK(s->pdf_solid_angle == 1.0f);
    CHECK(s->distance == doctest::Approx(d).epsilon(1e-6));
    const double irradiance = s->radiance[2] * dot(s->wi, ref.normal) / s->pdf_solid_angle;
    CHECK(irradiance == doctest::Approx(intensity / (d * d)).epsilon(1e-6));
    CHECK(light.pdf_li(ref, s->wi, nullptr) == 0.0f);
  }
}

TEST_CASE("point light power is 4 pi I times the band width") {
  // ∫ over 360-830 nm of a constant I is 470 I (trapezoid rule: exact), and an isotropic point emits 4π I.
  const PointLight light({1, 2, 3}, constant(0.5));
  CHECK(light.total_power_w(0.0) == doctest::Approx(4.0 * std::numbers::pi * 0.5 * 470.0).epsilon(1e-12));
  CHECK(light.is_delta());
}

TEST_CASE("point light at the reference point gives no sample") {
  const PointLight light({1, 1, 1}, constant(1.0));
  CHECK_FALSE(light.sample_li({{1, 1, 1}, {0, 0, 1}}, kLambda, {0.5f, 0.5f}));
  // A black light has nothing to give either.
  CHECK_FALSE(PointLight({0, 0, 5}, constant(0.0)).sample_li({{0, 0, 0}, {0, 0, 1}}, kLambda, {0.5f, 0.5f}));
}

TEST_CASE("spot light falloff: full inside, smoothstep in cos between, zero outside") {
  const SpotLight spot({0, 0, 0}, {0, 0, -2}, 20.0, 40.0, constant(3.0));
  auto at_angle = [](double deg) {
    const double r = deg * std::numbers::pi / 180.0;
    return Vec3(float(std::sin(r)), 0.0f, float(-std::cos(r)));
  };
  CHECK(spot.falloff(at_angle(0)) == 1.0f);
  CHECK(spot.falloff(at_angle(19.9)) == 1.0f);
  CHECK(spot.falloff(at_angle(40.1)) == 0.0f);
  // Halfway in cos θ the smoothstep is 1/2.
  const double mid_cos = 0.5 * (std::cos(20.0 * std::numbers::pi / 180) + std::cos(40.0 * std::numbers::pi / 180));
  CHECK(spot.falloff(at_angle(std::acos(mid_cos) * 180 / std::numbers::pi)) == doctest::Approx(0.5).epsilon(1e-5));
  // Irradiance at a point below, 30° off axis at distance 2: I s(cos 30°) / 4 on a patch facing the light.
  const Vec3 dir = at_angle(30.0);
  const LightReference ref{dir * 2.0f, -dir};
  const auto s = spot.sample_li(ref, kLambda, {0.1f, 0.1f});
  REQUIRE(s);
  const double t = (std::cos(30.0 * std::numbers::pi / 180) - std::cos(40.0 * std::numbers::pi / 180)) /
                   (std::cos(20.0 * std::numbers::pi / 180) - std::cos(40.0 * std::numbers::pi / 180));
  CHECK(s->radiance[0] == doctest::Approx(3.0 * t * t * (3 - 2 * t) / 4.0).epsilon(1e-5));
  // Outside the outer cone there is no sample.
  CHECK_FALSE(spot.sample_li({at_angle(45.0) * 2.0f, {0, 0, 1}}, kLambda, {0.1f, 0.1f}));
  CHECK_FALSE(spot.sample_li({{0, 0, 1}, {0, 0, -1}}, kLambda, {0.1f, 0.1f}));  // behind the light
}

TEST_CASE("spot light power matches numerical integration of its cone") {
  // Φ = ∫ I s(θ) dω = 2π I ∫₀^π s(θ) sin θ dθ, integrated here by Simpson's rule in θ (4000 intervals), against the
  // closed form 2π I (1 − (cos θi + cos θo)/2) that total_power_w uses. The smoothstep has zero slope at both
  // cone edges, so the integrand is C¹ and Simpson with h = π/4000 is accurate to ~1e-7 relative; 1e-5 allows for
  // the float falloff. (A hard edge is a step, which Simpson handles only to O(h); it is checked analytically below.)
  for (auto [inner, outer] : {std::pair{20.0, 40.0}, std::pair{0.0, 90.0}, std::pair{60.0, 170.0}}) {
    CAPTURE(inner);
    CAPTURE(outer);
    const SpotLight spot({0, 0, 0}, {0, 1, 0}, inner, outer, constant(1.0));
    const int n = 4000;
    const double h = std::numbers::pi / n;
    double integral = 0;
    for (int i = 0; i <= n; ++i) {
      const double theta = i * h;
      const double f = spot.falloff({float(std::sin(theta)), float(std::cos(theta)), 0.0f}) * std::sin(theta);
      integral += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    const double numeric_w = 2.0 * std::numbers::pi * integral * h / 3.0 * 470.0;
    CHECK(spot.total_power_w(0.0) == doctest::Approx(numeric_w).epsilon(1e-5));
  }
  // Hard edge at 30°: Φ = 2π I (1 − cos 30°), the solid angle of the cone.
  const SpotLight hard({0, 0, 0}, {0, 1, 0}, 30.0, 30.0, constant(1.0));
  CHECK(hard.total_power_w(0.0) ==
        doctest::Approx(2.0 * std::numbers::pi * (1.0 - std::cos(std::numbers::pi / 6)) * 470.0).epsilon(1e-12));
  CHECK(hard.falloff({0.0f, 1.0f, 0.0f}) == 1.0f);
  CHECK(hard.falloff({0.6f, 0.8f, 0.0f}) == 0.0f);  // 36.9° off axis
}

TEST_CASE("projection light: which pixel lights where, its intensity, power and bounds") {
  // A 3 × 2 grey image (aspect 1.5: the screen is ±1.5 × ±1) projected with a 60° field across its shorter side, from
  // 2 m above the floor straight down, image right = world −x, image up = world +z (the frame a projector pointing
  // down with up +z has: right = axis × up). Pixel (c, r) covers screen x ∈ [−1.5 + c, −0.5 + c], y ∈ [1 − r − 1, 1 − r].
  const std::vector<float> pixels = {1, 2, 3, 4, 5, 6};  // row 0 (top): 1 2 3; row 1: 4 5 6
  const Frame frame{{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
  const double tan30 = std::tan(std::numbers::pi / 6.0), scale = 0.5;
  const ProjectionLight light({0, 2, 0}, frame, 60.0, std::make_shared<test::GreyImage>(3, 2, pixels), scale);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) {
      CAPTURE(c);
      CAPTURE(r);
      // The floor point under the pixel's centre: screen (−1 + c, 0.5 − r) · tan30 · 2 m along right and up.
      const double sx = (-1.0 + c) * tan30 * 2.0, sy = (0.5 - r) * tan30 * 2.0;
      const Vec3 floor_point{float(-sx), 0.0f, float(sy)};
      const auto s = light.sample_li({floor_point, {0, 1, 0}}, kLambda, {0.5f, 0.5f});
      REQUIRE(s);
      CHECK(s->is_delta);
      const double d2 = sx * sx + sy * sy + 4.0;
      CHECK(s->radiance[1] == doctest::Approx(scale * pixels[size_t(3 * r + c)] / d2).epsilon(1e-5));
    }
  // Outside the picture (beyond the long side's edge) and behind the projector: nothing.
  CHECK_FALSE(light.sample_li({{float(-1.6 * tan30 * 2.0), 0, 0}, {0, 1, 0}}, kLambda, {0.5f, 0.5f}));
  CHECK_FALSE(light.sample_li({{0, 3, 0}, {0, -1, 0}}, kLambda, {0.5f, 0.5f}));
  CHECK(light.pixel_towards({0, 1, 0}).first == -1);
  // Power: Σ I_pixel · Ω_pixel, each Ω the closed-form solid angle of the pixel's rectangle at distance 1, here
  // checked against a 600 × 400 midpoint rule of ∫ I cos³θ dA over the image plane (error < 1e-5).
  double power = 0.0;
  const int nx = 600, ny = 400;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = (-1.5 + 3.0 * (i + 0.5) / nx) * tan30, y = (1.0 - 2.0 * (j + 0.5) / ny) * tan30;
      const double cos3 = std::pow(1.0 + x * x + y * y, -1.5);
      power += scale * pixels[size_t(3 * (j * 2 / ny) + i * 3 / nx)] * cos3 * (3.0 * tan30 / nx) * (2.0 * tan30 / ny);
    }
  CHECK(light.total_power_w(1.0) == doctest::Approx(power * 470.0).epsilon(1e-5));  // a grey pixel: ∫dλ = 470 nm
  CHECK(light.luminance_weighted_solid_angle_sr() == doctest::Approx(power / scale).epsilon(1e-5));
  // Bounds: the brightest pixel, in the cone to the picture's corners.
  const auto b = light.part_bounds(0);
  REQUIRE(b);
  CHECK(b->intensity_w_sr == doctest::Approx(scale * 6.0 * 470.0).epsilon(1e-5));
  CHECK(light.corner_angle_rad() == doctest::Approx(std::atan(tan30 * std::hypot(1.5, 1.0))));
}
