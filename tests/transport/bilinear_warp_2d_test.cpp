// BilinearWarp2D, the conditional bilinear density of measured BRDFs: sample() draws from density(), invert()
// undoes sample(), and tables blended between parameter values stay consistent.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "square_chi_square.h"
#include "statistics.h"
#include "transport/sampling/bilinear_warp_2d.h"

using namespace rimu;

namespace bilinear_warp_test {

// A grid per combination of two parameters (3 × 2 values) of 7 × 5 positive values with structure: a ridge that
// moves with the parameters, and one cell row near zero.
BilinearWarp2D parametric_warp(std::vector<float>* raw = nullptr) {
  const int width = 7, height = 5;
  std::vector<float> values;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 2; ++b)
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const float ridge = std::exp(-0.5f * float((x - 2 * a - b) * (x - 2 * a - b)));
          values.push_back(y == 1 ? 1e-4f : 0.2f + ridge * float(1 + y + a));
        }
  if (raw) *raw = values;
  return BilinearWarp2D(values, width, height, {{0.0f, 0.5f, 2.0f}, {10.0f, 20.0f}}, BilinearWarp2D::Use::warp);
}

}  // namespace bilinear_warp_test

using namespace bilinear_warp_test;

TEST_CASE("bilinear warp: the density integrates to 1 for parameters at and between the tabulated values") {
  const BilinearWarp2D warp = parametric_warp();
  for (const auto& p : std::vector<std::vector<float>>{{0.0f, 10.0f}, {0.3f, 14.0f}, {1.7f, 20.0f}, {-5.0f, 99.0f}}) {
    double sum = 0.0;
    const int n = 600;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) sum += warp.density({(float(i) + 0.5f) / n, (float(j) + 0.5f) / n}, p);
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    CHECK(sum / (double(n) * n) == doctest::Approx(1.0).epsilon(1e-4));  // the midpoint rule's error on bilinear cells
  }
}

TEST_CASE("bilinear warp: invert() undoes sample(), and both report the density at the point") {
  const BilinearWarp2D warp = parametric_warp();
  std::mt19937 rng(7);
  for (int i = 0; i < 20000; ++i) {
    const Vec2 u{test::uniform01(rng), test::uniform01(rng)};
    const float p[2] = {2.5f * test::uniform01(rng) - 0.2f, 8.0f + 14.0f * test::uniform01(rng)};
    const auto s = warp.sample(u, p);
    const auto back = warp.invert(s.p, p);
    REQUIRE(std::isfinite(s.density));
    CHECK(s.density == doctest::Approx(warp.density(s.p, p)).epsilon(1e-4));
    CHECK(back.density == doctest::Approx(s.density).epsilon(1e-4));
    // The near-empty row's band maps a wide range of u to a thin strip, so compare u, where the map is steep,
    // with an absolute tolerance of float rounding in the CDFs.
    CHECK(std::fabs(back.p.x - u.x) < 2e-3f);
    CHECK(std::fabs(back.p.y - u.y) < 2e-3f);
  }
}

TEST_CASE("bilinear warp: sample() matches density() (chi-square) between the tabulated parameters") {
  const BilinearWarp2D warp = parametric_warp();
  const std::vector<std::vector<float>> parameters = {{0.25f, 12.5f}, {1.9f, 19.0f}, {0.5f, 10.0f}};
  const double threshold = test::sidak_threshold(0.01, int(parameters.size()));
  std::mt19937 rng(11);
  for (const auto& p : parameters) {
    const int cells = 24, draws = 200000;
    const auto expected = test::square_expected_counts([&](Vec2 x) { return warp.density(x, p); }, cells, 8, draws);
    std::vector<double> observed(expected.size(), 0.0);
    for (int i = 0; i < draws; ++i)
      observed[test::square_cell(warp.sample({test::uniform01(rng), test::uniform01(rng)}, p).p, cells)] += 1.0;
    const auto result = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(p[0]);
    CAPTURE(result.statistic);
    CAPTURE(result.degrees_of_freedom);
    CHECK(result.p_value > threshold);
  }
}

TEST_CASE("bilinear warp: an interpolant returns the given values at the grid points and blends parameters linearly") {
  std::vector<float> values = {1, 2, 3, 4, /* second grid */ 10, 20, 30, 40};
  const BilinearWarp2D table(values, 2, 2, {{500.0f, 600.0f}}, BilinearWarp2D::Use::interpolate);
  const float at500[1] = {500.0f}, at550[1] = {550.0f}, below[1] = {100.0f}, above[1] = {900.0f};
  CHECK(table.value({0, 0}, at500) == doctest::Approx(1));
  CHECK(table.value({1, 1}, at500) == doctest::Approx(4));
  CHECK(table.value({0.5f, 0.5f}, at500) == doctest::Approx(2.5));
  CHECK(table.value({1, 0}, at550) == doctest::Approx(11));  // (2 + 20)/2
  CHECK(table.value({0, 1}, below) == doctest::Approx(3));   // clamped to the first grid
  CHECK(table.value({0, 1}, above) == doctest::Approx(30));  // and to the last
  const float nan[1] = {NAN};
  CHECK(std::isfinite(table.value({0.3f, 0.3f}, nan)));
}

TEST_CASE("bilinear warp: values_along_last gives value() at each of four values of the last parameter") {
  std::vector<float> values;
  const int width = 5, height = 4;
  for (int a = 0; a < 3; ++a)
    for (int l = 0; l < 6; ++l)
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) values.push_back(float(1 + a) * 0.3f + float(l * l) * 0.1f + float(x * y) * 0.05f);
  const BilinearWarp2D table(values, width, height, {{0.0f, 1.0f, 3.0f}, {400, 450, 500, 600, 700, 830}},
                             BilinearWarp2D::Use::interpolate);
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 p{test::uniform01(rng), test::uniform01(rng)};
    const float leading[1] = {4.0f * test::uniform01(rng) - 0.5f};
    const std::array<float, 4> lambda = {350.0f + 500.0f * test::uniform01(rng), 400.0f, 830.0f, 612.5f};
    const std::array<float, 4> together = table.values_along_last(p, leading, lambda);
    for (size_t lane = 0; lane < 4; ++lane) {
      const float parameters[2] = {leading[0], lambda[lane]};
      CHECK(together[lane] == doctest::Approx(table.value(p, parameters)).epsilon(1e-6));
    }
  }
}
