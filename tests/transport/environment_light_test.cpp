// Environment lights: constant (irradiance πL), images sampled by luminance (chi-square against pdf_li, irradiance
// against quadrature), the direction convention, black and single-pixel images, and power.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numeric>
#include <numbers>
#include <vector>

#include "grey_environment_image.h"
#include "light_test_support.h"
#include "square_chi_square.h"
#include "transport/lights/environment_light.h"
#include "test_support.h"

using namespace rimu;

namespace {
using rimu::test::kLambda;
using rimu::test::kPi;

using test::GreyImage;

/// A 16 × 8 image with a bright blob, a dark band and a gradient.
std::shared_ptr<GreyImage> test_image() {
  std::vector<float> v(16 * 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) v[y * 16 + x] = (y == 5 ? 0.0f : 0.1f + 0.05f * x) + (x == 3 && y == 2 ? 40.0f : 0.0f);
  return std::make_shared<GreyImage>(16, 8, v);
}

/// ∫ L(ω) max(0, n·ω) dω over the sphere by a fine midpoint rule in (u, v) (dω = 2π² sin θ du dv).
double irradiance_quadrature(const EnvironmentLight& env, Vec3 normal, int nu, int nv) {
  double sum = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const Vec2 uv{(i + 0.5f) / nu, (j + 0.5f) / nv};
      const Vec3 d = env.uv_to_direction(uv);
      sum += env.radiance_escaped(d, kLambda)[0] * std::max(0.0f, dot(d, normal)) * 2 * kPi * kPi *
             std::sin(kPi * uv.y) / (double(nu) * nv);
    }
  return sum;
}

test::MeanEstimate irradiance_estimate(const EnvironmentLight& env, const LightReference& ref, int n, unsigned seed) {
  std::mt19937 rng(seed);
  test::MeanEstimate e;
  for (int i = 0; i < n; ++i) {
    const auto s = env.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    if (!s) {
      e.add(0.0);
      continue;
    }
    REQUIRE(s->pdf_solid_angle == doctest::Approx(env.pdf_li(ref, s->wi)).epsilon(1e-6));
    e.add(s->radiance[0] * std::max(0.0f, dot(s->wi, ref.normal)) / s->pdf_solid_angle);
  }
  return e;
}
}  // namespace

TEST_CASE("constant environment light: irradiance pi L, power 4 pi^2 r^2 L") {
  const EnvironmentLight env(LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 0.7));
  const auto e = irradiance_estimate(env, {{1, 2, 3}, normalize({1, -1, 2})}, 40000, 30);
  CAPTURE(e.standard_error());
  CHECK(std::abs(e.mean() - kPi * 0.7) <= test::kMonteCarloSigmas * e.standard_error());
  CHECK(env.total_power_w(2.0) == doctest::Approx(4 * kPi * kPi * 4.0 * 0.7 * 470.0).epsilon(1e-12));
  CHECK(env.is_infinite());
}

TEST_CASE("environment direction convention: u = 0 along +s, v = 0 at +n, u grows to the right") {
  const EnvironmentLight z_up(test_image(), 1.0);
  auto uv = z_up.direction_to_uv({1, 0, 0});
  CHECK(uv.x == doctest::Approx(0.0));
  CHECK(uv.y == doctest::Approx(0.5));
  // Looking along +x with +z up, the right-hand side is −y: a quarter turn to the right is u = 1/4.
  CHECK(z_up.direction_to_uv({0, -1, 0}).x == doctest::Approx(0.25));
  CHECK(z_up.direction_to_uv({0, 0, 1}).y == doctest::Approx(0.0));
  // A y-up frame: n = +y, s = +x, t = −z.
  const EnvironmentLight y_up(test_image(), 1.0, Frame{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});
  CHECK(y_up.direction_to_uv({0, 1, 0}).y == doctest::Approx(0.0));
  CHECK(y_up.direction_to_uv({1, 0, 0}).x == doctest::Approx(0.0));
  CHECK(y_up.direction_to_uv({0, 0, 1}).x == doctest::Approx(0.25));  // right of +x when +y is up (right-handed)
  // Round trips.
  for (Vec2 p : {Vec2{0.1f, 0.2f}, Vec2{0.7f, 0.9f}, Vec2{0.5f, 0.5f}}) {
    const Vec2 back = y_up.direction_to_uv(y_up.uv_to_direction(p));
    CHECK(back.x == doctest::Approx(p.x).epsilon(1e-5));
    CHECK(back.y == doctest::Approx(p.y).epsilon(1e-5));
  }
  // The bright pixel (3, 2) is what radiance_escaped returns at its centre.
  CHECK(z_up.radiance_escaped(z_up.uv_to_direction({3.5f / 16, 2.5f / 8}), kLambda)[0] == doctest::Approx(40.25f));
}

TEST_CASE("environment image sampling matches pdf_li, by chi-square over image cells") {
  // Cells: 2 × 2 per pixel (32 × 16). Expected counts are N ∫_cell pdf_li dω = N ∫∫ pdf_li(ω(u,v)) 2π² sin θ du dv,
  // integrated by 4 × 4 midpoints per cell; the product is constant on a pixel, so this is exact up to float
  // rounding, but it still checks pdf_li's Jacobian against the samples' actual distribution.
  for (bool rotated : {false, true}) {
    CAPTURE(rotated);
    const Frame frame = rotated ? Frame::from_normal(normalize({0.3f, 1.0f, -0.4f})) : Frame{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const EnvironmentLight env(test_image(), 2.0, frame);
    const int nu = 32, nv = 16, sub = 4, n = 200000;
    std::vector<double> observed(nu * nv, 0.0);
    // dω = 2π² sin(πv) du dv on the equirectangular image.
    const std::vector<double> expected = test::square_expected_counts(
        [&](Vec2 uv) { return env.pdf_li({}, env.uv_to_direction(uv)) * 2 * kPi * kPi * std::sin(kPi * uv.y); }, nu,
        nv, sub, n);
    CHECK(std::accumulate(expected.begin(), expected.end(), 0.0) / n == doctest::Approx(1.0).epsilon(1e-4));
    std::mt19937 rng(31);
    for (int s = 0; s < n; ++s) {
      const auto ls = env.sample_li({}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
      REQUIRE(ls);
      REQUIRE(std::isinf(ls->distance));
      REQUIRE(ls->pdf_solid_angle == env.pdf_li({}, ls->wi));
      const Vec2 uv = env.direction_to_uv(ls->wi);
      observed[test::square_cell(uv, nu, nv)] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(chi.statistic);
    CHECK(chi.p_value > test::kChiSquareAlpha);
  }
}

TEST_CASE("environment image: a deferred sample is sample_li's, its radiance filled in by resolve_radiance") {
  const EnvironmentLight env(test_image(), 2.0, Frame::from_normal(normalize({0.3f, 1.0f, -0.4f})));
  std::mt19937 rng(8);
  for (int s = 0; s < 2000; ++s) {
    const Vec2 u{test::uniform01(rng), test::uniform01(rng)};
    const auto full = env.sample_li({}, kLambda, u);
    auto deferred = env.sample_part_li_deferred(0, {}, kLambda, u);
    REQUIRE(full);
    REQUIRE(deferred);
    CHECK_FALSE(full->radiance_pending);
    CHECK(deferred->radiance_pending);
    CHECK(deferred->wi == full->wi);
    CHECK(deferred->pdf_solid_angle == full->pdf_solid_angle);
    env.resolve_radiance(*deferred, kLambda);
    CHECK_FALSE(deferred->radiance_pending);
    for (int k = 0; k < 4; ++k) CHECK(deferred->radiance[k] == full->radiance[k]);
    env.resolve_radiance(*deferred, kLambda);  // a resolved sample is left as it is
    CHECK(deferred->radiance[0] == full->radiance[0]);
  }
}

TEST_CASE("environment image irradiance by light sampling matches quadrature") {
  // The quadrature (1024 × 512 midpoints; the image is piecewise constant, so its error is the pixel edges',
  // ~1e-3 relative) against the Monte Carlo estimate within kMonteCarloSigmas standard errors plus that 1e-3.
  const EnvironmentLight env(test_image(), 1.5);
  for (Vec3 normal : {Vec3{0, 0, 1}, normalize(Vec3{1, 0.5f, 0.2f}), Vec3{0, 0, -1}}) {
    const double exact = irradiance_quadrature(env, normal, 1024, 512);
    const auto e = irradiance_estimate(env, {{0, 0, 0}, normal}, 40000, 32);
    CAPTURE(exact);
    CAPTURE(e.mean());
    CAPTURE(e.standard_error());
    CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + 1e-3 * exact);
  }
  // Power: 4π² r² × the solid-angle mean of ∫L dλ; the image is grey, so ∫L dλ = 470 L and the 16-wavelength
  // rule is exact. The mean radiance is Σ L_xy Ω_y / 4π with Ω_y the pixel's exact solid angle.
  double mean = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      mean += 1.5 * test_image()->at(x, y) * (2 * kPi / 16) * (std::cos(kPi * y / 8) - std::cos(kPi * (y + 1) / 8));
  mean /= 4 * kPi;
  CHECK(env.total_power_w(3.0) == doctest::Approx(4 * kPi * kPi * 9.0 * mean * 470.0).epsilon(1e-5));
}

TEST_CASE("environment image with a single bright pixel") {
  std::vector<float> v(64 * 32, 0.0f);
  v[10 * 64 + 40] = 1000.0f;
  const EnvironmentLight env(std::make_shared<GreyImage>(64, 32, v), 1.0);
  const Vec3 normal = normalize(env.uv_to_direction({40.5f / 64, 10.5f / 32}));
  std::mt19937 rng(33);
  int in_pixel = 0;
  for (int i = 0; i < 10000; ++i) {
    const auto s = env.sample_li({}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(s);
    const Vec2 uv = env.direction_to_uv(s->wi);
    in_pixel += int(uv.x * 64) == 40 && int(uv.y * 32) == 10;
  }
  // The luminance floor sends 1e-3 × mean × Σ sin θ / (pixel + floor) ≈ 0.1 % of the samples elsewhere.
  CHECK(in_pixel >= 9950);
  CHECK(env.sampling_block() == 1);  // a block would spread the pixel's samples over its dark neighbours
  const double exact = irradiance_quadrature(env, normal, 64 * 16, 32 * 16);
  const auto e = irradiance_estimate(env, {{0, 0, 0}, normal}, 20000, 34);
  CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + 1e-3 * exact);
}

TEST_CASE("a smooth environment image is sampled from coarser tables, still matching pdf_li and the quadrature") {
  // 256 × 128 pixels of a slow variation with a soft bright region: the sampling tables take blocks of pixels
  // (distribution_coarsening.h), and sampling, density and irradiance must stay consistent with the pixels.
  const int w = 256, h = 128;
  std::vector<float> v(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = (x + 0.5 - 80.0) / 30.0, dy = (y + 0.5 - 40.0) / 20.0;
      v[size_t(y) * w + x] = float(0.2 + 0.1 * std::sin(2 * kPi * x / w) + 3.0 * std::exp(-(dx * dx + dy * dy)));
    }
  const EnvironmentLight env(std::make_shared<GreyImage>(w, h, v), 1.0);
  CHECK(env.sampling_block() >= 2);
  const int nu = 64, nv = 32, sub = 4, n = 200000;
  const std::vector<double> expected = test::square_expected_counts(
      [&](Vec2 uv) { return env.pdf_li({}, env.uv_to_direction(uv)) * 2 * kPi * kPi * std::sin(kPi * uv.y); }, nu, nv,
      sub, n);
  CHECK(std::accumulate(expected.begin(), expected.end(), 0.0) / n == doctest::Approx(1.0).epsilon(1e-3));
  std::vector<double> observed(nu * nv, 0.0);
  std::mt19937 rng(41);
  for (int s = 0; s < n; ++s) {
    const auto ls = env.sample_li({}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(ls);
    REQUIRE(ls->pdf_solid_angle == env.pdf_li({}, ls->wi));
    observed[test::square_cell(env.direction_to_uv(ls->wi), nu, nv)] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);
  for (Vec3 normal : {Vec3{0, 0, 1}, normalize(Vec3{0.6f, -0.7f, 0.3f})}) {
    const double exact = irradiance_quadrature(env, normal, w * 4, h * 4);
    const auto e = irradiance_estimate(env, {{0, 0, 0}, normal}, 40000, 42);
    CAPTURE(exact);
    CAPTURE(e.mean());
    CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + 1e-3 * exact);
  }
}

TEST_CASE("black environment images") {
  SUBCASE("radiance without luminance falls back to uniform sphere sampling") {
    auto image = std::make_shared<GreyImage>(8, 4, std::vector<float>(32, 2.0f));
    image->luminance_zero_ = true;
    const EnvironmentLight env(image, 1.0);
    CHECK(env.pdf_li({}, {0, 0, 1}) == doctest::Approx(1.0 / (4 * kPi)));
    const auto e = irradiance_estimate(env, {{0, 0, 0}, {0, 1, 0}}, 40000, 35);
    CHECK(std::abs(e.mean() - kPi * 2.0) <= test::kMonteCarloSigmas * e.standard_error());
  }
  SUBCASE("an all-black image has no power and gives no samples") {
    const EnvironmentLight env(std::make_shared<GreyImage>(8, 4, std::vector<float>(32, 0.0f)), 1.0);
    CHECK(env.total_power_w(10.0) == 0.0);
    CHECK_FALSE(env.sample_li({}, kLambda, {0.5f, 0.5f}));
    CHECK(env.pdf_li({}, {0, 0, 1}) == 0.0f);
  }
}

TEST_CASE("environment combined with BSDF sampling: a constant one is left to it, an image samples above its mean") {
  // Constant: not sampled by next-event estimation at all (density 0), unless combined is off again.
  EnvironmentLight constant(LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 2.0));
  const LightReference surface{{0, 0, 0}, {0, 0, 1}}, medium{{0, 0, 0}, {0, 0, 0}};
  constant.set_combined_with_bsdf_sampling(true);
  CHECK_FALSE(constant.sampled_by_nee());
  CHECK_FALSE(constant.sample_li(surface, kLambda, {0.3f, 0.6f}));
  CHECK(constant.pdf_li(surface, {0, 0, 1}) == 0.0f);
  constant.set_combined_with_bsdf_sampling(false);
  CHECK(constant.sampled_by_nee());
  CHECK(constant.pdf_li(surface, {0, 0, 1}) == doctest::Approx(1.0 / (4.0 * kPi)));

  // Image: from a surface point, the density follows max(0, Y − Ȳ) (Ȳ the solid-angle mean): zero on pixels below
  // the mean, and sampled frequencies match pdf_li (chi-square); from a point in a medium, the full density.
  const std::shared_ptr<GreyImage> image = test_image();
  EnvironmentLight full(image, 2.0), combined(image, 2.0);
  combined.set_combined_with_bsdf_sampling(true);
  CHECK(combined.sampled_by_nee());
  double weighted = 0, weight = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const double s = std::sin(kPi * (y + 0.5) / 8);
      weighted += s * image->luminance(x, y);
      weight += s;
    }
  const double mean = weighted / weight;
  int below = 0, above = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const Vec3 d = combined.uv_to_direction({(x + 0.5f) / 16, (y + 0.5f) / 8});
      CAPTURE(x);
      CAPTURE(y);
      if (image->luminance(x, y) <= mean) {
        CHECK(combined.pdf_li(surface, d) == 0.0f);
        ++below;
      } else {
        CHECK(combined.pdf_li(surface, d) > 0.0f);
        ++above;
      }
      CHECK(combined.pdf_li(medium, d) == full.pdf_li(medium, d));
    }
  CHECK(below > 0);
  CHECK(above > 0);
  const int nu = 32, nv = 16, sub = 4, n = 200000;
  const std::vector<double> expected = test::square_expected_counts(
      [&](Vec2 uv) { return combined.pdf_li(surface, combined.uv_to_direction(uv)) * 2 * kPi * kPi * std::sin(kPi * uv.y); },
      nu, nv, sub, n);
  CHECK(std::accumulate(expected.begin(), expected.end(), 0.0) / n == doctest::Approx(1.0).epsilon(1e-4));
  std::vector<double> observed(nu * nv, 0.0);
  std::mt19937 rng(37);
  for (int s = 0; s < n; ++s) {
    const auto ls = combined.sample_li(surface, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(ls);
    REQUIRE(ls->pdf_solid_angle == combined.pdf_li(surface, ls->wi));
    observed[test::square_cell(combined.direction_to_uv(ls->wi), nu, nv)] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);
}
