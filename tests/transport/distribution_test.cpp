// Piecewise-constant distributions: discrete and continuous sampling against their pdf by chi-square, zero-weight
// bins, and the 2D marginal/conditional construction.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "light_test_support.h"
#include "transport/sampling/distribution_1d.h"
#include "transport/sampling/distribution_2d.h"

using namespace rimu;

TEST_CASE("Distribution1D discrete sampling follows the weights and never picks a zero weight") {
  const std::vector<double> weights = {0.0, 3.0, 0.0, 0.0, 1.0, 0.5, 7.0, 0.0, 2.5, 0.0};
  const Distribution1D d(weights);
  CHECK(d.sum() == doctest::Approx(14.0));
  double total_probability = 0;
  for (int i = 0; i < d.size(); ++i) total_probability += d.probability(i);
  CHECK(total_probability == doctest::Approx(1.0).epsilon(1e-6));

  const int n = 100000;
  std::mt19937 rng(1);
  std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
  for (size_t i = 0; i < weights.size(); ++i) expected[i] = n * weights[i] / d.sum();
  for (int s = 0; s < n; ++s) {
    const auto pick = d.sample_discrete(test::uniform01(rng));
    REQUIRE(weights[pick.index] > 0.0);
    CHECK(pick.probability == doctest::Approx(weights[pick.index] / 14.0));
    observed[pick.index] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);

  // The edges of the unit interval and every CDF boundary land on positive bins.
  for (float u : {0.0f, 3.0f / 14.0f, 4.0f / 14.0f, 4.5f / 14.0f, 11.5f / 14.0f, std::nextafter(1.0f, 0.0f)}) {
    CAPTURE(u);
    const auto pick = d.sample_discrete(u);
    CHECK(weights[pick.index] > 0.0);
    CHECK(pick.u_remapped >= 0.0f);
    CHECK(pick.u_remapped < 1.0f);
  }
}

TEST_CASE("Distribution1D remapped u is uniform in the chosen bin") {
  // sample_discrete hands the rest of u to the next decision (a point on the chosen triangle): it must be uniform.
  const std::vector<double> weights = {1.0, 4.0, 2.0};
  const Distribution1D d(weights);
  const int n = 50000, bins = 20;
  std::mt19937 rng(2);
  std::vector<double> observed(bins, 0.0), expected(bins, double(n) / bins);
  for (int s = 0; s < n; ++s) observed[int(d.sample_discrete(test::uniform01(rng)).u_remapped * bins)] += 1;
  CHECK(test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one).p_value > test::kChiSquareAlpha);
}

TEST_CASE("Distribution1D continuous sampling matches its pdf") {
  const std::vector<double> weights = {0.2, 0.0, 1.0, 5.0, 0.0, 0.0, 2.0, 0.7};
  const Distribution1D d(weights);
  // p(x) = n f_i / S integrates to 1: Σ p_i / n.
  double integral = 0;
  for (int i = 0; i < d.size(); ++i) integral += d.pdf((i + 0.5f) / d.size()) / d.size();
  CHECK(integral == doctest::Approx(1.0).epsilon(1e-6));
  CHECK(d.pdf(-0.1f) == 0.0f);
  CHECK(d.pdf(1.1f) == 0.0f);

  // 64 histogram cells, 8 per bin: the density is constant within a bin, so the expected counts are exact.
  const int n = 200000, cells = 64;
  std::mt19937 rng(3);
  std::vector<double> observed(cells, 0.0), expected(cells);
  for (int c = 0; c < cells; ++c) expected[c] = double(n) / cells * d.pdf((c + 0.5f) / cells);
  for (int s = 0; s < n; ++s) {
    const auto x = d.sample_continuous(test::uniform01(rng));
    REQUIRE(x.x >= 0.0f);
    REQUIRE(x.x < 1.0f);
    REQUIRE(x.pdf == d.pdf(x.x));
    observed[int(x.x * cells)] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);
}

TEST_CASE("Distribution1D with zero weights is empty") {
  const std::vector<double> zeros = {0.0, 0.0, 0.0};
  const Distribution1D d(zeros);
  CHECK(d.is_zero());
  CHECK(d.probability(1) == 0.0f);
  CHECK(d.pdf(0.5f) == 0.0f);
  CHECK(Distribution1D().is_zero());
}

TEST_CASE("Distribution1D keeps tiny bins among a million") {
  // Float cumulative sums would lose a 1e-7 bin next to 1e6 unit bins; the double CDF keeps its probability.
  std::vector<double> weights(1000000, 1.0);
  weights[777777] = 1e-7;
  const Distribution1D d(weights);
  CHECK(d.probability(777777) == doctest::Approx(1e-13).epsilon(1e-3));
  CHECK(d.probability(777778) == doctest::Approx(1.0 / 999999.0000001).epsilon(1e-6));
  // u = 0.5 falls in bin 499999: its upper CDF edge is 500000/999999.0000001 > 0.5.
  CHECK(d.sample_discrete(0.5f).index == 499999);
}

TEST_CASE("Distribution2D sampling matches its pdf, with empty rows and columns") {
  const int w = 6, h = 4;
  // A zero row (y = 1), a zero column (x = 4), and a strong cell.
  std::vector<double> weights = {
      1, 2, 3, 1, 0, 1,  //
      0, 0, 0, 0, 0, 0,  //
      2, 1, 9, 1, 0, 3,  //
      1, 1, 1, 1, 0, 0.5};
  const Distribution2D d(weights, w, h);
  double total = 0;
  for (double x : weights) total += x;
  const int sub = 2, n = 200000;  // 2 × 2 histogram cells per grid cell
  std::vector<double> observed(w * h * sub * sub, 0.0), expected(observed.size());
  for (int y = 0; y < h * sub; ++y)
    for (int x = 0; x < w * sub; ++x) {
      // p(u, v) = w h f / S, constant on each grid cell; a histogram cell covers 1/(w h sub²) of the square.
      const Vec2 uv{(x + 0.5f) / (w * sub), (y + 0.5f) / (h * sub)};
      const double exact = w * h * weights[(y / sub) * w + x / sub] / total;
      CHECK(d.pdf(uv) == doctest::Approx(exact).epsilon(1e-5));
      expected[y * w * sub + x] = n * exact / (w * h * sub * sub);
    }
  std::mt19937 rng(4);
  for (int s = 0; s < n; ++s) {
    const auto p = d.sample({test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(weights[p.y * w + p.x] > 0.0);
    REQUIRE(p.pdf == doctest::Approx(d.pdf(p.uv)).epsilon(1e-6));
    observed[int(p.uv.y * h * sub) * w * sub + int(p.uv.x * w * sub)] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);
}
