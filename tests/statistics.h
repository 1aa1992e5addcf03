// Statistics shared by the tests of every folder: Pearson's chi-square test with its p-value, the Šidák
// correction, the mean and standard error of a sample, Simpson quadrature (for expected counts), and a
// reproducible uniform random source. One copy here, so that every chi-square test in the suite is judged alike.
#pragma once

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace rimu::test {

/// A uniform float in [0, 1) from 24 random bits (std::generate_canonical<float> can return 1: LWG 2524).
inline float uniform01(std::mt19937& rng) { return float(rng() >> 8) * 0x1p-24f; }

/// Simpson's rule for ∫_lo^hi f with n (even) intervals.
template <typename F>
double simpson(F&& f, double lo, double hi, int n) {
  const double h = (hi - lo) / n;
  double sum = f(lo) + f(hi);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(lo + i * h);
  return sum * h / 3.0;
}

/// Regularised upper incomplete gamma Q(a, x) = Γ(a, x)/Γ(a) (Abramowitz & Stegun 6.5.29 and 6.5.31).
/// For x < a + 1 the power series P(a, x) = e^(−x) xᵃ Σₙ xⁿ/Γ(a + n + 1) converges fast and Q = 1 − P; otherwise
/// Legendre's continued fraction Γ(a, x) = e^(−x) xᵃ · 1/(x + 1 − a − 1(1 − a)/(x + 3 − a − 2(2 − a)/(...)))
/// does, evaluated front to back by the modified Lentz method. Both are run to full double precision (~1e-15).
inline double regularized_gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefactor = a * std::log(x) - x - std::lgamma(a);  // log(e^(−x) xᵃ / Γ(a))
  if (x < a + 1.0) {
    // Terms xⁿ Γ(a)/Γ(a + n + 1), each the previous times x/(a + n); stop once they no longer change the sum.
    double term = 1.0 / a, series = term;
    for (int n = 1; n < 1000 && std::abs(term) > 1e-17 * std::abs(series); ++n) {
      term *= x / (a + n);
      series += term;
    }
    return 1.0 - std::exp(log_prefactor) * series;
  }
  // Lentz: f = b₀ + a₁/(b₁ + a₂/(b₂ + ...)) as a product of ratios Cₙ Dₙ; `tiny` stands in for a zero denominator.
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, fraction = d;
  for (int n = 1; n < 1000; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double step = d * c;
    fraction *= step;
    if (std::abs(step - 1.0) < 1e-16) break;
  }
  return std::exp(log_prefactor) * fraction;
}

/// P(X ≥ statistic) for X ~ χ²(k): the chi-square survival function, Q(k/2, statistic/2).
inline double chi_square_p_value(double statistic, int degrees_of_freedom) {
  return regularized_gamma_q(0.5 * degrees_of_freedom, 0.5 * statistic);
}

/// The per-test significance for `test_count` independent tests at family-wise level `alpha` (Šidák 1967):
/// 1 − (1 − alpha)^(1/test_count).
inline double sidak_threshold(double alpha, int test_count) { return 1.0 - std::pow(1.0 - alpha, 1.0 / test_count); }

/// Pearson's approximation by χ² is valid when every cell expects at least this many counts; sparser cells are
/// pooled (the usual rule of thumb).
inline constexpr double kPearsonMinExpected = 5.0;

/// How pearson_chi_square() pools the cells that expect fewer than kPearsonMinExpected counts. The two rules come
/// from two families of tests and are kept as they were, so that no test's verdict changes:
enum class Pooling {
  /// Neighbouring cells are merged, in index order, until the group expects ≥ 5; the last group is closed
  /// whatever it holds. Suits histograms of one ordered variable (wavelength, filter offset), where a sparse
  /// tail is pooled with the cells next to it. A cell that expects nothing gets no special treatment.
  adjacent,
  /// Every cell that expects < 5 goes into one pooled cell, counted if it expects anything at all. A cell that
  /// expects nothing but received samples fails the test outright (statistic ∞, p = 0): the sampler produced
  /// something its pdf says is impossible. Used by the light and distribution tests.
  sparse_into_one,
};

struct ChiSquareResult {
  double statistic = 0;
  int degrees_of_freedom = 0;
  double p_value = 1;
};

/// Pearson's chi-square of observed against expected counts (same length), after pooling the sparse cells as
/// `pooling` says; degrees of freedom = cells after pooling − 1.
inline ChiSquareResult pearson_chi_square(const std::vector<double>& observed, const std::vector<double>& expected,
                                          Pooling pooling) {
  ChiSquareResult r;
  double pooled_obs = 0.0, pooled_exp = 0.0;
  int cells = 0;
  const auto add_cell = [&](double obs, double exp) {
    r.statistic += (obs - exp) * (obs - exp) / exp;
    ++cells;
  };
  for (size_t i = 0; i < observed.size(); ++i) {
    if (pooling == Pooling::adjacent) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      if (pooled_exp >= kPearsonMinExpected || i + 1 == observed.size()) {
        add_cell(pooled_obs, pooled_exp);
        pooled_obs = pooled_exp = 0.0;
      }
      continue;
    }
    if (expected[i] <= 0.0 && observed[i] > 0.0) return {INFINITY, 0, 0.0};
    if (expected[i] < kPearsonMinExpected) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      continue;
    }
    add_cell(observed[i], expected[i]);
  }
  if (pooling == Pooling::sparse_into_one && pooled_exp > 0.0) add_cell(pooled_obs, pooled_exp);
  r.degrees_of_freedom = cells - 1;
  r.p_value = chi_square_p_value(r.statistic, r.degrees_of_freedom);
  return r;
}

/// Mean and standard error of the mean (sample standard deviation / √n) of a list of values, in two passes.
inline std::pair<double, double> mean_and_standard_error(const std::vector<double>& values) {
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= double(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - mean) * (v - mean);
  const double variance = squares / double(values.size() - 1);
  return {mean, std::sqrt(variance / double(values.size()))};
}

}  // namespace rimu::test
