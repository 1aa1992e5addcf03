// Triangle-mesh area lights: sampling against pdf_li by chi-square, irradiance of a square against its closed form
// at three scales, sides, degenerate triangles, grazing and on-light reference points, and power.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "light_test_support.h"
#include "transport/lights/area_light.h"

using namespace rimu;

namespace {
const SampledWavelengths kLambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f / 470.0f));
LightSpectrum constant(double value) { return LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), value); }

/// A square of half-side a at height h, centred on the z axis, emitting downwards (towards the origin).
AreaLight square_light(double a, double h, double radiance, bool two_sided) {
  const float fa = float(a), fh = float(h);
  const std::vector<Vec3> v = {{-fa, -fa, fh}, {fa, -fa, fh}, {fa, fa, fh}, {-fa, fa, fh}};
  const std::vector<uint32_t> idx = {0, 2, 1, 0, 3, 2};  // clockwise from above: the normal is −z
  return AreaLight(v, idx, constant(radiance), two_sided);
}

/// Irradiance at the origin (normal +z) from the square above: E = 4 L · s · atan(s), s = a/√(a² + h²).
/// It is the view factor from a differential element to a parallel rectangle whose corner lies on the element's
/// normal, F = (1/2π)[X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))] with X = Y = a/h (Howell, "A Catalog
/// of Radiation Heat Transfer Configuration Factors"), times πL, over the four quadrants. The test below also
/// checks it against direct quadrature of ∫∫ L h² / (x² + y² + h²)² dx dy.
double square_irradiance(double a, double h, double radiance) {
  const double s = a / std::sqrt(a * a + h * h);
  return 4.0 * radiance * s * std::atan(s);
}

/// Monte Carlo irradiance ∫ L cos θ dω at `ref` by light sampling (samples below the tangent plane count 0).
test::MeanEstimate irradiance_estimate(const AreaLight& light, const LightReference& ref, int n, unsigned seed) {
  return test::light_sampling_irradiance(light, ref, kLambda, n, seed);
}
}  // namespace

TEST_CASE("the closed form of a square's irradiance matches quadrature") {
  // Midpoint rule on a 2000² grid over the square: the integrand is smooth, error O(1/n²) ≈ 1e-7 relative.
  const double a = 0.5, h = 0.8;
  const int n = 2000;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -a + (i + 0.5) * 2 * a / n, y = -a + (j + 0.5) * 2 * a / n;
      const double r2 = x * x + y * y + h * h;
      sum += h * h / (r2 * r2);
    }
  CHECK(sum * (2 * a / n) * (2 * a / n) == doctest::Approx(square_irradiance(a, h, 1.0)).epsilon(1e-6));
}

TEST_CASE("area light irradiance of a 1 m2 square on its axis matches the closed form at three scales") {
  // Scale invariance: a square of half-side 0.5 s at height s gives the same E for s = 1e-4 m, 1 m and 1e5 m.
  const double radiance = 3.0;
  for (double scale : {1e-4, 1.0, 1e5}) {
    CAPTURE(scale);
    const AreaLight light = square_light(0.5 * scale, scale, radiance, false);
    CHECK(light.area_m2() == doctest::Approx(scale * scale).epsilon(1e-6));
    const auto e = irradiance_estimate(light, {{0, 0, 0}, {0, 0, 1}}, 40000, 20);
    const double exact = square_irradiance(0.5 * scale, scale, radiance);
    CAPTURE(e.mean());
    CAPTURE(e.standard_error());
    CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error());
  }
}

TEST_CASE("one-sided area lights are dark from behind, two-sided ones are not") {
  const AreaLight one = square_light(0.5, 1.0, 2.0, false), two = square_light(0.5, 1.0, 2.0, true);
  const LightReference above{{0, 0, 2}, {0, 0, -1}};  // behind the light, looking down at it
  CHECK_FALSE(one.sample_li(above, kLambda, {0.3f, 0.6f}));
  const auto e = irradiance_estimate(two, above, 40000, 21);
  CHECK(std::abs(e.mean() - square_irradiance(0.5, 1.0, 2.0)) <= test::kMonteCarloSigmas * e.standard_error());
  SurfaceHit hit;
  hit.position = {0, 0, 1};
  hit.primitive = 1;
  CHECK(one.radiance(hit, {0, 0, -1}, kLambda)[0] == doctest::Approx(2.0));
  CHECK(one.radiance(hit, {0, 0, 1}, kLambda)[0] == 0.0f);
  CHECK(two.radiance(hit, {0, 0, 1}, kLambda)[0] == doctest::Approx(2.0));
  CHECK(one.pdf_li(above, {0, 0, -1}, &hit) == 0.0f);
  // Power: π A ∫L dλ per side, with ∫ over 360-830 nm of a constant = 470.
  CHECK(one.total_power_w(0) == doctest::Approx(std::numbers::pi * 1.0 * 2.0 * 470.0).epsilon(1e-6));
  CHECK(two.total_power_w(0) == doctest::Approx(2.0 * std::numbers::pi * 1.0 * 2.0 * 470.0).epsilon(1e-6));
}

TEST_CASE("area light sampling matches pdf_li over the light's solid angle, by chi-square") {
  // A mesh in the plane z = 0: the rectangle [0,2]×[0,1] in three front-facing (+z) triangles of areas 0.25, 0.75
  // and 1, two back-facing (−z) triangles over [2,3]×[0,1], and a degenerate one. Seen from an off-axis point
  // above, each histogram cell is the set of directions that hit a 0.1 × 0.1 m patch of the plane, so the
  // expected count is N ∫_cell p_ω dω = N ∫_patch pdf_li(x → y) |cos θ_l| / d² dA, integrated by 4 × 4 midpoints.
  // Samples behind the one-sided light fail (std::nullopt): they form one more cell, expected N (1 − Σ).
  const std::vector<Vec3> v = {{0, 0, 0}, {0.5f, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {3, 0, 0}, {3, 1, 0}};
  const std::vector<uint32_t> idx = {0, 1, 4, 1, 2, 3, 1, 3, 4, /*back*/ 2, 6, 5, 2, 3, 6, /*degenerate*/ 0, 1, 2};
  const AreaLight light(v, idx, constant(1.0), false);
  CHECK(light.degenerate_triangle_count() == 1);
  CHECK(light.area_m2() == doctest::Approx(3.0));
  // Which triangle holds a point of the plane (barycentric test in 2D), -1 if none.
  auto triangle_at = [&](float x, float y) {
    for (int k = 0; k < 5; ++k) {
      const Vec3 a = v[idx[3 * k]], b = v[idx[3 * k + 1]], c = v[idx[3 * k + 2]];
      const float d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      const float l1 = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / d;
      const float l2 = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / d;
      if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) return k;
    }
    return -1;
  };
  const LightReference ref{{0.4f, 1.6f, 0.9f}, {0, 0, -1}};
  const int nx = 30, ny = 10, n = 150000, sub = 4;
  std::vector<double> observed(nx * ny + 1, 0.0), expected(nx * ny + 1, 0.0);
  double total = 0;
  for (int cy = 0; cy < ny; ++cy)
    for (int cx = 0; cx < nx; ++cx) {
      double integral = 0;
      for (int j = 0; j < sub; ++j)
        for (int i = 0; i < sub; ++i) {
          const float x = (cx + (i + 0.5f) / sub) * 0.1f, y = (cy + (j + 0.5f) / sub) * 0.1f;
          SurfaceHit hit;
          hit.position = {x, y, 0};
          const int k = triangle_at(x, y);
          if (k < 0) continue;
          hit.primitive = uint32_t(k);
          const Vec3 to = hit.position - ref.position;
          const float d2 = length_squared(to);
          const Vec3 wi = to / std::sqrt(d2);
          integral += light.pdf_li(ref, wi, &hit) * std::fabs(wi.z) / d2 * (0.01 / (sub * sub));
        }
      expected[cy * nx + cx] = n * integral;
      total += integral;
    }
  CHECK(total == doctest::Approx(2.0 / 3.0).epsilon(1e-4));  // front area / total area
  expected[nx * ny] = n * (1.0 - total);
  std::mt19937 rng(22);
  for (int s = 0; s < n; ++s) {
    const auto ls = light.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    if (!ls) {
      observed[nx * ny] += 1;
      continue;
    }
    const Vec3 y = ref.position + ls->wi * ls->distance;
    SurfaceHit hit;
    hit.position = y;
    hit.primitive = uint32_t(std::max(0, triangle_at(y.x, y.y)));
    // pdf_li for the same direction and hit gives the density sample_li reported.
    REQUIRE(light.pdf_li(ref, ls->wi, &hit) == doctest::Approx(ls->pdf_solid_angle).epsilon(1e-4));
    const int cx = std::clamp(int(y.x / 0.1f), 0, nx - 1), cy = std::clamp(int(y.y / 0.1f), 0, ny - 1);
    observed[cy * nx + cx] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CAPTURE(chi.degrees_of_freedom);
  CHECK(chi.p_value > test::kChiSquareAlpha);
  // The degenerate triangle has no density.
  SurfaceHit degenerate;
  degenerate.position = {1, 0, 0};
  degenerate.primitive = 5;
  CHECK(light.pdf_li(ref, normalize(degenerate.position - ref.position), &degenerate) == 0.0f);
}

TEST_CASE("area light hard cases: all degenerate, grazing, reference on the light") {
  SUBCASE("a mesh of degenerate triangles has no area, no power and no samples") {
    const std::vector<Vec3> v = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}};
    const std::vector<uint32_t> idx = {0, 1, 2, 0, 3, 3};
    const AreaLight light(v, idx, constant(1.0), true);
    CHECK(light.degenerate_triangle_count() == 2);
    CHECK(light.area_m2() == 0.0);
    CHECK(light.total_power_w(0) == 0.0);
    CHECK_FALSE(light.sample_li({{0, 0, 5}, {0, 0, -1}}, kLambda, {0.5f, 0.5f}));
  }
  SUBCASE("a reference point in the light's plane sees it edge-on: no samples, no NaN") {
    const AreaLight light = square_light(0.5, 1.0, 1.0, true);
    std::mt19937 rng(23);
    for (int i = 0; i < 1000; ++i) {
      const auto s = light.sample_li({{3, 0, 1}, {0, 0, 1}}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
      CHECK_FALSE(s);
    }
    SurfaceHit hit;
    hit.position = {0.5f, 0, 1};
    hit.primitive = 0;
    CHECK(light.pdf_li({{3, 0, 1}, {0, 0, 1}}, {-1, 0, 0}, &hit) == 0.0f);
  }
  SUBCASE("nearly grazing: densities are huge but finite") {
    const AreaLight light = square_light(0.5, 1.0, 1.0, false);
    std::mt19937 rng(24);
    for (int i = 0; i < 1000; ++i) {
      const auto s = light.sample_li({{3, 0, 1 - 1e-5f}, {-1, 0, 0}}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
      if (!s) continue;
      CHECK(std::isfinite(s->pdf_solid_angle));
      CHECK(s->pdf_solid_angle > 0.0f);
      CHECK(std::isfinite(s->radiance[0] / s->pdf_solid_angle));
    }
  }
  SUBCASE("a reference point on the light itself") {
    // Every sampled point is in the reference's plane (cos θ_l = 0) or the point itself (d = 0): nothing to sample.
    const AreaLight light = square_light(0.5, 1.0, 1.0, false);
    std::mt19937 rng(25);
    for (int i = 0; i < 1000; ++i)
      CHECK_FALSE(light.sample_li({{0.1f, 0.2f, 1}, {0, 0, -1}}, kLambda, {test::uniform01(rng), test::uniform01(rng)}));
  }
}
