// Statistics shared by the light and distribution tests: Pearson's chi-square with its p-value, Monte Carlo
// estimates with their standard error, and a reproducible uniform random source.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace rimu::test {

/// A uniform float in [0, 1) from 24 random bits (std::generate_canonical<float> can return 1: LWG 2524).
inline float uniform01(std::mt19937& rng) { return float(rng() >> 8) * 0x1p-24f; }

/// Regularised upper incomplete gamma Q(a, x); the chi-square survival function is Q(k/2, x/2).
/// Series for x < a + 1, continued fraction (modified Lentz) otherwise: Abramowitz & Stegun 6.5.29 and 6.5.31.
inline double upper_incomplete_gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_front = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, total = term;
    for (int n = 1; n < 10000 && term > 1e-16 * total; ++n) total += (term *= x / (a + n));
    return 1.0 - std::exp(log_front) * total;
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int n = 1; n < 10000; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < tiny ? tiny : d;
    c = b + an / c;
    c = std::abs(c) < tiny ? tiny : c;
    d = 1.0 / d;
    h *= d * c;
    if (std::abs(d * c - 1.0) < 1e-15) break;
  }
  return std::exp(log_front) * h;
}

struct ChiSquareResult {
  double statistic = 0;
  int degrees_of_freedom = 0;
  double p_value = 1;
};

/// Pearson's chi-square of observed against expected counts. Cells expected below 5 are pooled into one cell
/// (the approximation's usual validity condition); an expected-zero cell that received samples makes the test
/// fail outright (p = 0): the sampler produced something its pdf says is impossible.
inline ChiSquareResult chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
  ChiSquareResult r;
  double pooled_obs = 0, pooled_exp = 0;
  int cells = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] <= 0.0 && observed[i] > 0.0) return {INFINITY, 0, 0.0};
    if (expected[i] < 5.0) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      continue;
    }
    r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pooled_exp > 0.0) {
    r.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++cells;
  }
  r.degrees_of_freedom = cells - 1;
  r.p_value = upper_incomplete_gamma_q(0.5 * r.degrees_of_freedom, 0.5 * r.statistic);
  return r;
}

/// Significance level of every chi-square test here. The seeds are fixed, so a test is deterministic; 1e-3 keeps
/// the chance that a correct sampler was unlucky with the chosen seed small.
inline constexpr double kChiSquareAlpha = 1e-3;

/// Mean and standard error of the mean of a stream of Monte Carlo samples.
struct MeanEstimate {
  double sum = 0, sum_squares = 0;
  long n = 0;
  void add(double x) {
    sum += x;
    sum_squares += x * x;
    ++n;
  }
  double mean() const { return sum / n; }
  double standard_error() const {
    const double m = mean();
    return std::sqrt(std::max(0.0, sum_squares / n - m * m) / (n - 1));
  }
};

/// How many standard errors a Monte Carlo mean may lie from the exact value: 5σ (a Gaussian two-sided tail of
/// 6e-7), so the check fails only for a real bias, not for an unlucky seed.
inline constexpr double kMonteCarloSigmas = 5.0;

}  // namespace rimu::test
