// Equal-area octahedral environments (pbrt-v4's environment maps): the square ↔ sphere map against values worked
// by hand from its formulas, its area preservation (uniform directions fill the square uniformly, by chi-square),
// and the light's importance sampling against its pdf (chi-square) and against the irradiance by quadrature.
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
#include "transport/sampling/equal_area_square.h"
#include "test_support.h"

using namespace rimu;

namespace equal_area_environment_test {
using rimu::test::kLambda;
using rimu::test::kPi;

using test::GreyImage;

/// A 16 × 16 image with a bright pixel, a dark column and a gradient.
std::shared_ptr<GreyImage> test_image() {
  std::vector<float> v(16 * 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) v[y * 16 + x] = (x == 9 ? 0.0f : 0.1f + 0.05f * y) + (x == 3 && y == 12 ? 60.0f : 0.0f);
  return std::make_shared<GreyImage>(16, 16, v);
}

void check_direction(Vec3 got, Vec3 expected) {
  CAPTURE(got.x);
  CAPTURE(got.y);
  CAPTURE(got.z);
  CHECK(got.x == doctest::Approx(expected.x).epsilon(1e-5));
  CHECK(got.y == doctest::Approx(expected.y).epsilon(1e-5));
  CHECK(got.z == doctest::Approx(expected.z).epsilon(1e-5));
}

TEST_CASE("equal-area square: landmarks and a point worked by hand") {
  check_direction(equal_area_square_to_sphere({0.5f, 0.5f}), {0, 0, 1});
  check_direction(equal_area_square_to_sphere({1.0f, 0.5f}), {1, 0, 0});
  check_direction(equal_area_square_to_sphere({0.0f, 0.5f}), {-1, 0, 0});
  check_direction(equal_area_square_to_sphere({0.5f, 1.0f}), {0, 1, 0});
  check_direction(equal_area_square_to_sphere({0.5f, 0.0f}), {0, -1, 0});
  for (Vec2 corner : {Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}, Vec2{1, 1}}) check_direction(equal_area_square_to_sphere(corner), {0, 0, -1});
  // (u, v) = (0.8125, 0.4375): a = 0.625, b = −0.125, r = 1 − |1 − 0.75| = 0.75, φ = (π/4)(−0.5/0.75 + 1) = π/12,
  // z = 1 − r² = 0.4375, r√(2 − r²) = 0.75·√1.4375; x = +cos φ·that, y = −sin φ·that.
  const double radial = 0.75 * std::sqrt(1.4375);
  check_direction(equal_area_square_to_sphere({0.8125f, 0.4375f}),
                  {float(std::cos(kPi / 12) * radial), float(-std::sin(kPi / 12) * radial), 0.4375f});
  // Its mirror image through the diamond's edge is the lower hemisphere: (a, b) = (0.875, −0.375) → z = −0.4375.
  CHECK(equal_area_square_to_sphere({0.9375f, 0.3125f}).z == doctest::Approx(-0.4375));
}

TEST_CASE("equal-area square: round trips in both directions") {
  for (int j = 0; j < 41; ++j)
    for (int i = 0; i < 41; ++i) {
      const Vec2 p{(i + 0.25f) / 41.0f, (j + 0.6f) / 41.0f};
      const Vec3 d = equal_area_square_to_sphere(p);
      REQUIRE(length(d) == doctest::Approx(1.0).epsilon(1e-5));
      const Vec2 back = equal_area_sphere_to_square(d);
      CHECK(back.x == doctest::Approx(p.x).epsilon(2e-5));
      CHECK(back.y == doctest::Approx(p.y).epsilon(2e-5));
    }
}

TEST_CASE("equal-area square: the float mapping (polynomial atan) follows the definition evaluated in double") {
  // The header's formulas in double with atan2: r = sqrt(1 − |z|), φ/(π/2) = atan2(|y|, |x|)/(π/2), b = φ·r,
  // a = r − b, mirrored into the corners below the horizon. Allowed per point: the polynomial atan's 1.3e-7 rad
  // (8.3e-8 of the quadrant, halved in u, v) plus float rounding of a few 6e-8 ulps, 2e-7 together; and near the
  // poles the cancellation in 1 − |z| (an absolute error up to 2⁻²⁴ becomes 2⁻²⁴/(2r) in r), 6e-8/r.
  std::mt19937 rng(47);
  double worst = 0.0;  // the error in units of the allowance
  for (int s = 0; s < 200000; ++s) {
    const Vec3 d = test::uniform_sphere_direction(rng);
    const double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
    const double x = std::fabs(d.x) / len, y = std::fabs(d.y) / len, z = std::fabs(d.z) / len;
    const double r = std::sqrt(std::max(0.0, 1.0 - z));
    double b = std::atan2(y, x) / (kPi / 2) * r, a = r - b;
    if (d.z < 0.0f) {
      std::swap(a, b);
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const double u = 0.5 * (std::copysign(a, double(d.x)) + 1.0), v = 0.5 * (std::copysign(b, double(d.y)) + 1.0);
    const Vec2 got = equal_area_sphere_to_square(d);
    const double allowed = 2e-7 + 6e-8 / std::max(r, 1e-3);
    worst = std::max({worst, std::fabs(got.x - u) / allowed, std::fabs(got.y - v) / allowed});
  }
  CAPTURE(worst);
  CHECK(worst < 1.0);
}

TEST_CASE("equal-area square: uniform directions land uniformly on the square (chi-square)") {
  // Area preservation: if every region of area A covers 4π·A steradians, uniform sphere directions fall into each
  // of the 24 × 24 cells with probability 1/576.
  const int cells = 24, n = 288000;
  std::vector<double> observed(cells * cells, 0.0), expected(cells * cells, double(n) / (cells * cells));
  std::mt19937 rng(41);
  for (int s = 0; s < n; ++s) {
    const Vec2 p = equal_area_sphere_to_square(test::uniform_sphere_direction(rng));
    observed[test::square_cell(p, cells)] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);
}

TEST_CASE("equal-area environment: sampling matches pdf_li (chi-square), pdf = p(u, v)/4pi, irradiance") {
  for (bool mirrored : {false, true}) {
    CAPTURE(mirrored);
    // A rotated frame, and the same with t negated: pbrt's light transform may mirror.
    Frame frame = Frame::from_normal(normalize({0.3f, 1.0f, -0.4f}));
    if (mirrored) frame.t = frame.t * -1.0f;
    const EnvironmentLight env(test_image(), 2.0, frame, EnvironmentMapping::equal_area_octahedral);
    // The bright pixel's centre is where its radiance comes from.
    CHECK(env.radiance_escaped(env.uv_to_direction({3.5f / 16, 12.5f / 16}), kLambda)[0] == doctest::Approx(2.0 * 60.7));
    const int cells = 32, n = 200000;
    std::vector<double> observed(cells * cells, 0.0);
    // dω = 4π du dv; pdf_li is constant on a cell (a quarter pixel), so one midpoint is exact.
    const std::vector<double> expected = test::square_expected_counts(
        [&](Vec2 uv) { return env.pdf_li({}, env.uv_to_direction(uv)) * 4 * kPi; }, cells, 1, n);
    CHECK(std::accumulate(expected.begin(), expected.end(), 0.0) / n == doctest::Approx(1.0).epsilon(1e-4));
    std::mt19937 rng(43);
    for (int s = 0; s < n; ++s) {
      const auto ls = env.sample_li({}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
      REQUIRE(ls);
      REQUIRE(ls->pdf_solid_angle == env.pdf_li({}, ls->wi));
      const Vec2 uv = env.direction_to_uv(ls->wi);
      observed[test::square_cell(uv, cells)] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(chi.statistic);
    CHECK(chi.p_value > test::kChiSquareAlpha);

    // Irradiance on three normals: light sampling against a 512 × 512 midpoint quadrature over the square.
    for (Vec3 normal : {Vec3{0, 0, 1}, normalize(Vec3{1, 0.5f, 0.2f}), frame.n}) {
      double exact = 0;
      for (int j = 0; j < 512; ++j)
        for (int i = 0; i < 512; ++i) {
          const Vec3 d = env.uv_to_direction({(i + 0.5f) / 512, (j + 0.5f) / 512});
          exact += env.radiance_escaped(d, kLambda)[0] * std::max(0.0f, dot(d, normal)) * 4 * kPi / (512.0 * 512.0);
        }
      test::MeanEstimate e;
      for (int s = 0; s < 40000; ++s) {
        const auto ls = env.sample_li({}, kLambda, {test::uniform01(rng), test::uniform01(rng)});
        REQUIRE(ls);
        e.add(ls->radiance[0] * std::max(0.0f, dot(ls->wi, normal)) / ls->pdf_solid_angle);
      }
      CAPTURE(exact);
      CAPTURE(e.mean());
      CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + 1e-3 * exact);
    }
  }
  // Power: every pixel subtends 4π/256 sr, so the solid-angle mean radiance is the plain pixel mean.
  double mean = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) mean += 1.5 * test_image()->at(x, y) / 256.0;
  const EnvironmentLight env(test_image(), 1.5, Frame{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, EnvironmentMapping::equal_area_octahedral);
  CHECK(env.total_power_w(3.0) == doctest::Approx(4 * kPi * kPi * 9.0 * mean * 470.0).epsilon(1e-5));
}

}  // namespace equal_area_environment_test
