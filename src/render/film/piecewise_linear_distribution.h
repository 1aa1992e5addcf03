// Sampling a 1D density proportional to a piecewise-linear function, by inverting its CDF exactly.
#pragma once

#include <vector>

namespace rimu {

/// The density p(x) ∝ f(x), where f is the linear interpolation of non-negative values f_i at equally spaced
/// knots x_i = lo + i·h over [lo, hi]. sample() inverts the CDF exactly (a quadratic per segment), so the samples
/// follow p with no tabulation error beyond f itself being the interpolant.
class PiecewiseLinearDistribution {
 public:
  /// Needs at least two knots, all values finite and ≥ 0, and a positive integral.
  PiecewiseLinearDistribution(double lo, double hi, std::vector<double> knot_values);

  /// Maps u in [0, 1) to x in [lo, hi] with density pdf(x). Cost: a guide-table lookup and a short scan (the
  /// segment is the one a binary search over the CDF would find; the film draws two per camera sample).
  double sample(double u) const;
  /// The normalised density at x (0 outside [lo, hi]).
  double pdf(double x) const;
  /// ∫ f dx over [lo, hi] (the normaliser).
  double integral() const { return integral_; }

 private:
  double lo_, hi_, step_;
  std::vector<double> f_;
  std::vector<double> cdf_;  // unnormalised ∫ f from lo to knot i
  // guide_[j]: the first knot whose CDF exceeds j/G of the integral (G = guide_.size()), where the scan for a
  // target in [j/G, (j+1)/G) of the integral starts: a binary search over 257 knots mispredicts ~8 branches per
  // call, which was 9 % of veach-mis's CPU time (docs/benchmarks.md, "Time to equal error, measured in CPU time").
  std::vector<unsigned> guide_;
  double integral_ = 0.0;
};

}  // namespace rimu
