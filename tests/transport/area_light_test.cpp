// Triangle-mesh area lights: sampling against pdf_li by chi-square, irradiance of a square against its closed form
// at three scales, sides, degenerate triangles, grazing and on-light reference points, and power.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "grey_environment_image.h"
#include "light_test_support.h"
#include "transport/lights/area_light.h"
#include "test_support.h"

using namespace rimu;

namespace {
using rimu::test::kLambda;
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

namespace {
/// The square of square_light (half-side a at height h, normal −z) with an emission image: u = (x + a)/2a and
/// v = (y + a)/2a at every corner, as a quad's uvs (0,0), (1,0), (1,1), (0,1) give.
AreaLight textured_square(double a, double h, std::shared_ptr<const RadianceImage> image, double scale) {
  const float fa = float(a), fh = float(h);
  const std::vector<Vec3> v = {{-fa, -fa, fh}, {fa, -fa, fh}, {fa, fa, fh}, {-fa, fa, fh}};
  const std::vector<uint32_t> idx = {0, 2, 1, 0, 3, 2};
  const Vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<std::array<Vec2, 3>> corners;
  for (size_t k = 0; k < 2; ++k) corners.push_back({uv[idx[3 * k]], uv[idx[3 * k + 1]], uv[idx[3 * k + 2]]});
  return AreaLight(v, idx, TexturedEmission(std::move(image), scale, std::move(corners)), false);
}

/// A ray from ref along wi against the square of textured_square: the hit (triangle, position, uv) or nothing.
std::optional<SurfaceHit> square_hit(double a, double h, const LightReference& ref, Vec3 wi) {
  if (!(wi.z > 0.0f)) return std::nullopt;
  const float t = (float(h) - ref.position.z) / wi.z;
  const Vec3 p = ref.position + wi * t;
  if (std::fabs(p.x) > a || std::fabs(p.y) > a) return std::nullopt;
  SurfaceHit hit;
  hit.position = p;
  hit.primitive = p.y > p.x ? 1u : 0u;  // triangle 0 = (v0, v2, v1) lies below the diagonal y = x
  hit.uv = {float((p.x + a) / (2 * a)), float((p.y + a) / (2 * a))};
  return hit;
}
}  // namespace

TEST_CASE("an area light with an emission image") {
  SUBCASE("a uniform image is the uniform light: same samples, densities, radiance, bounds and power") {
    const double c = 0.7, scale = 3.0;
    const AreaLight textured = textured_square(0.5, 1.0, std::make_shared<test::GreyImage>(3, 2, std::vector<float>(6, float(c))), scale);
    const AreaLight uniform = square_light(0.5, 1.0, c * scale, false);
    CHECK(textured.emitted_spectrum() == nullptr);
    CHECK(textured.total_power_w(0) == doctest::Approx(uniform.total_power_w(0)).epsilon(1e-6));
    std::mt19937 rng(31);
    for (int i = 0; i < 200; ++i) {
      const LightReference ref{{test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f, -test::uniform01(rng)}, {0, 0, 1}};
      const Vec2 u{test::uniform01(rng), test::uniform01(rng)};
      const auto a = textured.sample_li(ref, kLambda, u), b = uniform.sample_li(ref, kLambda, u);
      REQUIRE(bool(a) == bool(b));
      if (!a) continue;
      CHECK(a->pdf_solid_angle == doctest::Approx(b->pdf_solid_angle).epsilon(1e-5));
      CHECK(a->radiance[1] == doctest::Approx(b->radiance[1]).epsilon(1e-6));
      CHECK(length(a->wi - b->wi) < 1e-5f);
    }
    for (int part = 0; part < 2; ++part) {
      const auto a = textured.part_bounds(part), b = uniform.part_bounds(part);
      REQUIRE((a && b));
      CHECK(a->intensity_w_sr == doctest::Approx(b->intensity_w_sr).epsilon(1e-6));
    }
  }
  SUBCASE("left half bright, right half black: half the uniform square's irradiance on its axis") {
    // Two pixels (1 | 0): bilinear between their centres u = 1/4 and 3/4, clamped outside, so L(u) + L(1 − u) = 1
    // and, the geometry being symmetric under x → −x about the axis, E = E_uniform / 2 exactly.
    const AreaLight light = textured_square(0.5, 1.0, std::make_shared<test::GreyImage>(2, 1, std::vector<float>{1, 0}), 1.0);
    const auto e = irradiance_estimate(light, {{0, 0, 0}, {0, 0, 1}}, 40000, 32);
    CAPTURE(e.mean());
    CHECK(std::abs(e.mean() - 0.5 * square_irradiance(0.5, 1.0, 1.0)) <= test::kMonteCarloSigmas * e.standard_error());
    // Its power is half the uniform one's (by the same symmetry); the triangles' means are 16-point grids, whose
    // error on the ramp between the pixel centres is what the tolerance allows (they only choose triangles).
    CHECK(light.total_power_w(0) == doctest::Approx(0.5 * square_light(0.5, 1.0, 1.0, false).total_power_w(0)).epsilon(0.01));
    // The image's left (x = 0) column is at u < ½: x < 0 emits, x > 0 beyond the right pixel's centre does not.
    SurfaceHit hit;
    hit.primitive = 1;
    hit.uv = {0.1f, 0.9f};
    CHECK(light.radiance(hit, {0, 0, -1}, kLambda)[0] == doctest::Approx(1.0));
    hit.primitive = 0;
    hit.uv = {0.9f, 0.1f};
    CHECK(light.radiance(hit, {0, 0, -1}, kLambda)[0] == 0.0f);
  }
  SUBCASE("light sampling agrees with the radiance rays see, near (solid angle) and far (area), whole and by parts") {
    // A 4 × 3 image with a black pixel and a bright one, seen off-axis: the light-sampled irradiance (the radiance
    // at each sampled point's uv) against cosine-weighted directions that find the square and read radiance() at
    // the hit's uv. Both are unbiased estimates of the same integral, so they agree within their combined error.
    const std::vector<float> pixels = {0.2f, 1.0f, 0.0f, 0.5f, 4.0f, 0.3f, 0.1f, 0.9f, 0.6f, 0.0f, 2.0f, 0.4f};
    const auto image = std::make_shared<test::GreyImage>(4, 3, pixels);
    for (const double h : {0.4, 12.0}) {
      CAPTURE(h);
      const AreaLight light = textured_square(0.5, h, image, 2.0);
      const LightReference ref{{0.3f, -0.2f, 0}, {0, 0, 1}};
      const int n = 200000;
      const auto by_light = irradiance_estimate(light, ref, n, 33);
      test::MeanEstimate by_parts, by_rays;
      std::mt19937 rng(34);
      for (int i = 0; i < n; ++i) {
        const Vec2 u{test::uniform01(rng), test::uniform01(rng)};
        double sum = 0.0;
        for (int part = 0; part < 2; ++part)
          if (const auto s = light.sample_part_li(part, ref, kLambda, u))
            sum += s->radiance[0] * std::max(0.0f, s->wi.z) / s->pdf_solid_angle;
        by_parts.add(sum);
        // Cosine-weighted directions about +z: E = π · mean of L along them.
        const float r = std::sqrt(test::uniform01(rng)), phi = 2.0f * std::numbers::pi_v<float> * test::uniform01(rng);
        const Vec3 wi{r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - r * r))};
        const auto hit = square_hit(0.5, h, ref, wi);
        by_rays.add(hit ? std::numbers::pi * light.radiance(*hit, -wi, kLambda)[0] : 0.0);
        if (hit && i % 97 == 0) CHECK(light.pdf_li(ref, wi, &*hit) > 0.0f);
      }
      CAPTURE(by_light.mean());
      CAPTURE(by_parts.mean());
      CAPTURE(by_rays.mean());
      const auto agree = [](const test::MeanEstimate& x, const test::MeanEstimate& y) {
        return std::abs(x.mean() - y.mean()) <=
               test::kMonteCarloSigmas * std::hypot(x.standard_error(), y.standard_error());
      };
      CHECK(agree(by_light, by_rays));
      CHECK(agree(by_parts, by_rays));
    }
  }
}
