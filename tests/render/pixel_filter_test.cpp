// Pixel filters: importance-sampled offsets follow the filter (chi-square), with weight 1.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "render/film/piecewise_linear_distribution.h"
#include "render/film/pixel_filter.h"
#include "spectral/error.h"
#include "statistics.h"

using namespace rimu;

TEST_CASE("chi-square: filter offsets follow the analytic filter") {
  // 200k offsets (fixed seed) into a 16x16 grid over [-r, r]². Expected counts are N ∫∫_bin f / ∫∫ f from Simpson
  // quadrature of the analytic profile (separable, so a product of 1D integrals), not from the sampling tables:
  // this tests that the tabulation is fine enough as well as the inversion. Fails if p < 1e-3 (five filters:
  // family-wise false alarm < 0.5 % for a correct sampler, deterministic given the seed). 2D bins also test that
  // x and y are independent.
  const PixelFilter filters[] = {PixelFilter::box(0.5f), PixelFilter::triangle(1.0f), PixelFilter::gaussian(1.5f, 0.5f),
                                 PixelFilter::blackman_harris(2.0f), PixelFilter::gaussian(2.0f, 1.0f)};
  constexpr int kSamples = 200000, kBins = 16;
  for (const PixelFilter& filter : filters) {
    CAPTURE(filter.description());
    const double r = filter.radius_px(), width = 2.0 * r / kBins;
    auto profile = [&](double x) { return filter.profile(x); };
    const double total = test::simpson(profile, -r, r, 4000);
    std::vector<double> axis(kBins);
    for (int i = 0; i < kBins; ++i) axis[i] = test::simpson(profile, -r + i * width, -r + (i + 1) * width, 200) / total;
    std::vector<double> expected(kBins * kBins), observed(kBins * kBins, 0.0);
    for (int j = 0; j < kBins; ++j)
      for (int i = 0; i < kBins; ++i) expected[j * kBins + i] = kSamples * axis[i] * axis[j];

    std::mt19937 rng(20240501);
    int bad_weights = 0, outside = 0;
    for (int s = 0; s < kSamples; ++s) {
      const FilterSample sample = filter.sample(Vec2{test::uniform01(rng), test::uniform01(rng)});
      bad_weights += sample.weight != 1.0f;
      outside += !(std::abs(sample.offset_px.x) <= r && std::abs(sample.offset_px.y) <= r);
      const int i = std::min(kBins - 1, int((sample.offset_px.x + r) / width));
      const int j = std::min(kBins - 1, int((sample.offset_px.y + r) / width));
      observed[j * kBins + i] += 1.0;
    }
    CHECK(bad_weights == 0);
    CHECK(outside == 0);
    const auto [statistic, dof, p_value] = test::pearson_chi_square(observed, expected, test::Pooling::adjacent);
    CAPTURE(statistic);
    CAPTURE(dof);
    CHECK(p_value > 1e-3);
  }
}

TEST_CASE("the sampling density is the normalised filter") {
  // The density is the piecewise-linear interpolant of f₁ at 257 knots (h = r/128), normalised. Interpolation error
  // is at most h²/8·max|f₁''|: for the Gaussian σ = 0.5 (|f''| ≤ 1/σ² = 4) that is 1.2e-4 relative to f's peak 1,
  // for Blackman–Harris (|f''| ≤ (π/r)²(a₁ + 4a₂ + 9a₃) ≈ 2.7 at r = 2) 8e-5. 2e-4 of the peak covers both.
  for (const PixelFilter& filter : {PixelFilter::gaussian(1.5f, 0.5f), PixelFilter::blackman_harris(2.0f)}) {
    CAPTURE(filter.description());
    const double r = filter.radius_px();
    const double total_1d = test::simpson([&](double x) { return filter.profile(x); }, -r, r, 4000);
    const double peak = filter.profile(0.0) / total_1d;
    // pdf(x, y) = p₁(x) p₁(y), so p₁(x) = pdf(x, 0)/√pdf(0, 0).
    const double p1_at_0 = std::sqrt(filter.pdf(Vec2{0.0f, 0.0f}));
    for (double x = -r; x <= r; x += r / 37.0) {
      CAPTURE(x);
      const double exact = filter.profile(x) / total_1d;
      CHECK(std::abs(filter.pdf(Vec2{float(x), 0.0f}) / p1_at_0 - exact) <= 2e-4 * peak);
    }
    CHECK(filter.pdf(Vec2{float(r) * 1.01f, 0.0f}) == 0.0);
  }
  // The box is exact: 1/(2r)² everywhere inside.
  CHECK(PixelFilter::box(0.5f).pdf(Vec2{0.2f, -0.4f}) == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("filter shapes: Blackman-Harris is positive, the Gaussian reaches zero at its radius") {
  const PixelFilter bh = PixelFilter::blackman_harris(2.0f);
  // Harris 1978 4-term coefficients: peak a₀+a₁+a₂+a₃ = 1, ends a₀−a₁+a₂−a₃ = 6e-5 (to the coefficients' 5 decimals).
  CHECK(bh.profile(0.0) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(bh.profile(2.0) == doctest::Approx(6e-5).epsilon(1e-6));
  for (double x = -2.0; x <= 2.0; x += 0.01) CHECK(bh.profile(x) > 0.0);
  const PixelFilter g = PixelFilter::gaussian(1.5f, 0.5f);
  CHECK(g.profile(1.5) == 0.0);
  CHECK(g.profile(0.5) == doctest::Approx(std::exp(-0.5) - std::exp(-4.5)).epsilon(1e-12));
  CHECK_THROWS_AS(PixelFilter::gaussian(1.0f, 0.0f), InputError);
  CHECK_THROWS_AS(PixelFilter::box(-1.0f), InputError);
  CHECK_THROWS_AS(PixelFilter::blackman_harris(std::nanf("")), InputError);
}

TEST_CASE("the guide table finds the segment a binary search would: the same offsets bit for bit") {
  // A CDF with flat stretches (zero-valued knots) and steep ones, where a start in the wrong segment would show.
  std::vector<double> knots(65);
  for (size_t i = 0; i < knots.size(); ++i) knots[i] = (i % 16 < 5) ? 0.0 : double(i % 7) + 0.25 * double(i);
  const PiecewiseLinearDistribution d(-1.5, 1.5, knots);
  // The reference: the same inversion with std::upper_bound over the unnormalised CDF.
  std::vector<double> cdf(knots.size(), 0.0);
  const double step = 3.0 / 64.0;
  for (size_t i = 1; i < knots.size(); ++i) cdf[i] = cdf[i - 1] + 0.5 * step * (knots[i - 1] + knots[i]);
  auto reference = [&](double u) {
    const double target = u * cdf.back();
    size_t i = size_t(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
    i = std::clamp<size_t>(i, 1, knots.size() - 1) - 1;
    while (i + 1 < knots.size() - 1 && cdf[i + 1] == cdf[i]) ++i;
    const double a = knots[i], b = knots[i + 1];
    const double s = std::max(0.0, target - cdf[i]) / step;
    const double root = std::sqrt(std::max(0.0, a * a + 2.0 * (b - a) * s));
    const double t = a + root > 0.0 ? std::clamp(2.0 * s / (a + root), 0.0, 1.0) : 0.0;
    return std::min(1.5, -1.5 + (double(i) + t) * step);
  };
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> us{0.0, 1.0 / 256.0, 0.5, 255.0 / 256.0, std::nextafter(1.0, 0.0)};
  for (int i = 0; i < 100000; ++i) us.push_back(uniform(rng));
  for (int k = 0; k < 256; ++k) us.push_back(std::nextafter(double(k) / 256.0, 1.0));
  int mismatches = 0;
  for (double u : us) mismatches += d.sample(u) != reference(u) ? 1 : 0;
  CHECK(mismatches == 0);
}
