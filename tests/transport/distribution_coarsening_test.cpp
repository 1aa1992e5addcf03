// Coarser sampling tables (transport/sampling/distribution_coarsening.h): the added variance against its
// definition, a Monte Carlo estimate and exact cases; which block a smooth and a spiky table choose.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "light_test_support.h"
#include "transport/sampling/distribution_2d.h"
#include "transport/sampling/distribution_coarsening.h"

using namespace rimu;

namespace {
/// A smooth field on w × h: 1 + 0.5 sin(2πx/w) cos(πy/h), positive everywhere.
std::vector<float> smooth_weights(int w, int h) {
  std::vector<float> f(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      f[size_t(y) * w + x] = float(1.0 + 0.5 * std::sin(2 * test::kPi * (x + 0.5) / w) * std::cos(test::kPi * (y + 0.5) / h));
  return f;
}
}  // namespace

TEST_CASE("coarsening a table: exact added variance for constant blocks and a lone cell") {
  // Constant weights: a block is as good as its cells, R − 1 = 0 at every factor, and the coarsest allowed wins.
  const std::vector<float> constant(64 * 32, 2.5f);
  for (int f : {2, 4, 8, 16}) CHECK(coarsening_added_variance(constant, 64, 32, f) == doctest::Approx(0.0).epsilon(1e-12));
  CHECK(choose_sampling_block(constant, 64, 32, 0.01).factor == 16);
  CHECK(choose_sampling_block(constant, 64, 32, 0.01, 4).factor == 4);
  // One positive cell: the f × f block spreads its samples over f² cells, only one of which has weight, so
  // E[(f/p)²]/F² = f² and R − 1 = f² − 1.
  std::vector<float> lone(64 * 32, 0.0f);
  lone[17 * 64 + 41] = 3.0f;
  for (int f : {2, 4, 8}) CHECK(coarsening_added_variance(lone, 64, 32, f) == doctest::Approx(f * f - 1.0));
  CHECK(choose_sampling_block(lone, 64, 32, 0.01).factor == 1);
  // Only factors dividing both sides are tried: 48 × 24 admits 2, 4 and 8; 30 × 20 only 2.
  CHECK(choose_sampling_block(std::vector<float>(48 * 24, 1.0f), 48, 24, 0.01).factor == 8);
  CHECK(choose_sampling_block(std::vector<float>(30 * 20, 1.0f), 30, 20, 0.01).factor == 2);
  // R_f need not grow with f: one 2 × 2 block holding a single cell of 1 and three holding 0.5 everywhere sample
  // their 4 × 4 cells better as one block. R_2 = (4·1/1 + 3·4·1/2)/7 = 10/7, R_4 = 16·4/(7·7) = 64/49.
  std::vector<float> mixed(16, 0.5f);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) mixed[size_t(y) * 4 + x] = 0.0f;
  mixed[0] = 1.0f;
  CHECK(coarsening_added_variance(mixed, 4, 4, 2) == doctest::Approx(3.0 / 7.0));
  CHECK(coarsening_added_variance(mixed, 4, 4, 4) == doctest::Approx(15.0 / 49.0));
  // The search stops at the first factor over the limit (f = 2 here) and does not try f = 4 beyond it.
  CHECK(choose_sampling_block(mixed, 4, 4, 0.4).factor == 1);
  // All zero: nothing to lose.
  CHECK(coarsening_added_variance(std::vector<float>(16, 0.0f), 4, 4, 2) == 0.0);
}

TEST_CASE("coarsening a table: block sums keep the total, and the added variance is the table's own") {
  const int w = 128, h = 64;
  std::vector<float> f = smooth_weights(w, h);
  f[40 * w + 90] += 30.0f;  // a bright cell: the blocks around it are where coarsening costs
  const double total = std::accumulate(f.begin(), f.end(), 0.0);
  for (int factor : {2, 4, 8}) {
    CAPTURE(factor);
    const std::vector<float> sums = block_sums(f, w, h, factor);
    REQUIRE(sums.size() == size_t(w / factor) * (h / factor));
    CHECK(std::accumulate(sums.begin(), sums.end(), 0.0) == doctest::Approx(total).epsilon(1e-6));
    // The definition, R = (1/F²) Σ fᵢ²/pᵢ with pᵢ the coarse Distribution2D's own density over cell i (its pdf
    // at the cell centre, × the cell's area 1/(w h)), computed from the table rather than the formula.
    const Distribution2D coarse(sums, w / factor, h / factor);
    double r = 0.0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double p = coarse.pdf({(x + 0.5f) / w, (y + 0.5f) / h}) / (double(w) * h);
        const double fi = f[size_t(y) * w + x];
        r += fi * fi / p;
      }
    const double added = coarsening_added_variance(f, w, h, factor);
    CHECK(added == doctest::Approx(r / (total * total) - 1.0).epsilon(1e-4));
    // And by Monte Carlo: cells drawn from the coarse table, q = fᵢ/(pᵢ F) has mean 1 and variance R − 1 (checked
    // within kMonteCarloSigmas standard errors of the sample variance, from the sample's fourth moment).
    std::mt19937 rng{unsigned(factor)};
    const int n = 200000;
    std::vector<double> q(n);
    for (int s = 0; s < n; ++s) {
      const auto c = coarse.sample({test::uniform01(rng), test::uniform01(rng)});
      const int x = std::min(int(c.uv.x * w), w - 1), y = std::min(int(c.uv.y * h), h - 1);
      q[s] = f[size_t(y) * w + x] / (c.pdf / (double(w) * h) * total);
    }
    const double mean = std::accumulate(q.begin(), q.end(), 0.0) / n;
    double m2 = 0.0, m4 = 0.0;
    for (double v : q) {
      m2 += (v - mean) * (v - mean) / n;
      m4 += std::pow(v - mean, 4) / n;
    }
    const double mean_error = std::sqrt(m2 / n), variance_error = std::sqrt((m4 - m2 * m2) / n);
    CAPTURE(mean);
    CAPTURE(m2);
    CHECK(std::abs(mean - 1.0) <= test::kMonteCarloSigmas * mean_error);
    CHECK(std::abs(m2 - added) <= test::kMonteCarloSigmas * variance_error);
  }
}

TEST_CASE("coarsening a table: a smooth field takes blocks (its R growing with the block), a spike keeps its cells") {
  const int w = 256, h = 128;
  const std::vector<float> smooth = smooth_weights(w, h);
  double previous = 0.0;
  for (int factor : {2, 4, 8, 16}) {
    const double added = coarsening_added_variance(smooth, w, h, factor);
    CHECK(added >= previous);
    previous = added;
  }
  const SamplingBlock chosen = choose_sampling_block(smooth, w, h, 0.01);
  CHECK(chosen.factor >= 4);
  CHECK(chosen.added_variance <= 0.01);
  CHECK(chosen.added_variance == doctest::Approx(coarsening_added_variance(smooth, w, h, chosen.factor)).epsilon(1e-9));
  std::vector<float> spiky = smooth;
  spiky[77 * w + 3] = 1e4f;  // a sun of one pixel carrying most of the power
  CHECK(choose_sampling_block(spiky, w, h, 0.01).factor == 1);
}
