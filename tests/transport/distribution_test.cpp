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

TEST_CASE("Distribution2D over a large grid: guide-table searches agree with the pdf, at guide-cell edges too") {
  // 250 × 52 cells (15 guide cells per row, 3 for the marginal: k/15 and u·15 round, unlike powers of two), a third
  // of them empty, weights over 6 decades.
  const int w = 250, h = 52;
  std::mt19937 rng(7);
  std::vector<double> weights(size_t(w) * h);
  for (double& x : weights) {
    const float r = test::uniform01(rng);
    x = r < 0.33f ? 0.0 : std::pow(10.0, 6.0 * test::uniform01(rng));
  }
  for (int y = 0; y < h; ++y) weights[size_t(y) * w + 17] = 0.0;  // a whole empty column
  const Distribution2D d(weights, w, h);
  double total = 0;
  for (double x : weights) total += x;
  // The density is the weights' own to the float CDFs' rounding: a cell's share of its row, and a row's share of
  // the total, are differences of two CDF values in [0, 1], each within half an ulp (≤ 2⁻²⁵) of the exact sum.
  for (int y = 0; y < h; ++y) {
    double row_sum = 0;
    for (int x = 0; x < w; ++x) row_sum += weights[size_t(y) * w + x];
    for (int x = 0; x < w; ++x) {
      const double cell_share = weights[size_t(y) * w + x] / row_sum, row_share = row_sum / total;
      const double exact = double(w) * h * cell_share * row_share;
      const double rounding = double(w) * h * 0x1p-24 * (cell_share + row_share + 0x1p-24) + 1e-6 * exact;
      CAPTURE(x);
      CAPTURE(y);
      CHECK(std::abs(d.pdf({(x + 0.5f) / w, (y + 0.5f) / h}) - exact) <= rounding);
    }
  }
  // Every u near a guide cell's edge (k/15 across, k/3 down: ±4 ulps) lands on a positive cell whose density the
  // sample reports, and on the cell a search of the whole CDF finds (the first u with a larger CDF value is where
  // the cell changes, so its neighbours must agree with the cells that sample() gives nearby).
  const auto edges = [](int cells) {
    std::vector<float> out;
    for (int k = 0; k <= cells; ++k) {
      float u = std::min(float(k) / float(cells), std::nextafter(1.0f, 0.0f));
      for (int step = 0; step < 4; ++step) u = std::nextafter(u, 0.0f);
      for (int step = 0; step < 9; ++step, u = std::nextafter(u, 1.0f))
        if (u >= 0.0f && u < 1.0f) out.push_back(u);
    }
    return out;
  };
  // Sampling is monotone in u (inversion): along increasing u the chosen cell never moves back.
  for (float uy : edges(3)) {
    int previous_x = -1;
    for (float ux : edges(15)) {
      const auto s = d.sample({ux, uy});
      CHECK(s.x >= previous_x);
      previous_x = s.x;
    }
  }
  for (float ux : edges(15))
    for (float uy : edges(3)) {
      const auto s = d.sample({ux, uy});
      REQUIRE(weights[size_t(s.y) * w + s.x] > 0.0);
      CHECK(s.pdf == d.pdf(s.uv));
      CHECK(int(s.uv.x * w) == s.x);
      CHECK(int(s.uv.y * h) == s.y);
    }
  // Frequencies against the density, by chi-square over 32 × 16 blocks of cells.
  const int bx = 32, by = 16, n = 400000;
  std::vector<double> observed(bx * by, 0.0), expected(bx * by, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) expected[(y * by / h) * bx + x * bx / w] += n * weights[size_t(y) * w + x] / total;
  for (int i = 0; i < n; ++i) {
    const auto s = d.sample({test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(weights[size_t(s.y) * w + s.x] > 0.0);
    REQUIRE(s.pdf == d.pdf(s.uv));
    observed[(s.y * by / h) * bx + s.x * bx / w] += 1;
  }
  const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(chi.statistic);
  CHECK(chi.p_value > test::kChiSquareAlpha);
  CHECK(d.memory_bytes() < size_t(w) * h * 5);  // 4 B of CDF per cell and a guide entry per 16
}

TEST_CASE("Distribution2D's guide table at a cell edge where u·G rounds up past k/G") {
  // 176 equal cells, 11 guide cells: the CDF value c_80 = 5/11 (rounded to float) sits on guide edge k = 5, and
  // u = the float below it has u·11 rounded up to 5, so the guide's bracket starts one cell too far right unless
  // the search widens it. The answer is known: the last i with float(i/176) ≤ u.
  const int w = 176;
  const std::vector<double> weights(w, 1.0);
  const Distribution2D d(weights, w, 1);
  for (int k = 1; k < 11; ++k) {
    float u = std::nextafter(float(k) / 11.0f, 0.0f);
    for (int step = 0; step < 4; ++step) u = std::nextafter(u, 0.0f);
    for (int step = 0; step < 9; ++step, u = std::nextafter(u, 1.0f)) {
      int expected = 0;
      for (int i = 0; i < w; ++i)
        if (float(double(i) / w) <= u) expected = i;
      CAPTURE(k);
      CAPTURE(u);
      CHECK(d.sample({u, 0.5f}).x == expected);
    }
  }
}

TEST_CASE("Distribution2D from float weights is the double one's, to the weights' rounding") {
  // The same weights as floats and as the doubles those floats are: identical tables, so identical samples.
  const int w = 40, h = 17;
  std::mt19937 rng(21);
  std::vector<float> weights_f(size_t(w) * h);
  for (float& x : weights_f) x = test::uniform01(rng) < 0.2f ? 0.0f : std::pow(10.0f, 4.0f * test::uniform01(rng));
  const std::vector<double> weights_d(weights_f.begin(), weights_f.end());
  const Distribution2D from_float(std::span<const float>(weights_f), w, h), from_double(weights_d, w, h);
  for (int i = 0; i < 20000; ++i) {
    const Vec2 u{test::uniform01(rng), test::uniform01(rng)};
    const auto a = from_float.sample(u), b = from_double.sample(u);
    REQUIRE(a.x == b.x);
    REQUIRE(a.y == b.y);
    REQUIRE(a.uv.x == b.uv.x);
    REQUIRE(a.uv.y == b.uv.y);
    REQUIRE(a.pdf == b.pdf);
    REQUIRE(from_float.pdf(u) == from_double.pdf(u));
  }
}
