// Statistical helpers for the render tests: Pearson's chi-square test and Simpson quadrature.
// (The same maths as tests/spectral/sampled_wavelengths_test.cpp; a shared tests/ header would be the better home.)
#pragma once

#include <cmath>
#include <utility>
#include <vector>

namespace rimu::test {

/// Simpson's rule for ∫_lo^hi f with n (even) intervals.
template <typename F>
double simpson(F&& f, double lo, double hi, int n) {
  const double h = (hi - lo) / n;
  double sum = f(lo) + f(hi);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(lo + i * h);
  return sum * h / 3.0;
}

/// Regularised upper incomplete gamma Q(a, x): series for x < a + 1, Lentz's continued fraction otherwise
/// (Abramowitz & Stegun 6.5.29, 6.5.31).
inline double regularized_gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, series = term;
    for (int n = 1; n < 1000 && std::abs(term) > 1e-17 * std::abs(series); ++n) {
      term *= x / (a + n);
      series += term;
    }
    return 1.0 - std::exp(log_prefactor) * series;
  }
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

/// The p-value of a chi-square statistic with k degrees of freedom.
inline double chi_square_p_value(double statistic, int degrees_of_freedom) {
  return regularized_gamma_q(0.5 * degrees_of_freedom, 0.5 * statistic);
}

/// Pearson's statistic after pooling adjacent bins until each expected count is ≥ 5. Returns {statistic, dof}.
inline std::pair<double, int> pearson_chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
  double statistic = 0.0, obs = 0.0, exp = 0.0;
  int bins = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    obs += observed[i];
    exp += expected[i];
    if (exp >= 5.0 || i + 1 == observed.size()) {
      statistic += (obs - exp) * (obs - exp) / exp;
      ++bins;
      obs = exp = 0.0;
    }
  }
  return {statistic, bins - 1};
}

/// Mean and standard error of the mean (sample standard deviation / √n) of a list of values.
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
