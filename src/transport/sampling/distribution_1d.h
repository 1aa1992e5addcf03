// A piecewise-constant probability distribution over n bins: sampled discretely (pick a bin) or continuously
// (a point in [0, 1)). Lights use it to pick a light by power and a triangle by area; Distribution2D builds the
// environment map's marginal and conditional densities from it.
//
// Maths. Weights f_0..f_{n-1} ≥ 0 with sum S > 0 give
//   discrete:   P(i) = f_i / S,
//   continuous: p(x) = n·f_i / S for x in bin i = [i/n, (i+1)/n), which integrates to 1 over [0, 1).
// Both invert the cumulative sums c_i = Σ_{j<i} f_j / S (c_0 = 0, c_n = 1 exactly). For u in [0, 1) the chosen bin
// is the i with c_i ≤ u < c_{i+1}; since the inequality is strict, a zero-weight bin (c_i = c_{i+1}) can never be
// chosen, whatever u is, so callers never see a sample of zero probability.
//
// The cumulative sums are kept in double: a mesh light with a million triangles has bins of relative size 1e-6,
// the same order as float's spacing near 1, and float sums would give some triangles the wrong probability.
#pragma once

#include <span>
#include <vector>

namespace rimu {

class Distribution1D {
 public:
  /// Builds the distribution from non-negative, finite weights (asserted). All-zero (or no) weights give an
  /// empty distribution: is_zero() is true and it must not be sampled. Cost O(n).
  explicit Distribution1D(std::span<const double> weights);
  Distribution1D() = default;

  /// One bin chosen with probability f_i / S.
  struct DiscreteSample {
    int index = 0;
    float probability = 0;  ///< f_index / S, never 0
    /// The position of u inside the chosen bin, rescaled to [0, 1): a fresh uniform number for the next decision
    /// (e.g. the point on the chosen triangle). It has fewer significant bits left than u had.
    float u_remapped = 0;
  };
  /// Picks a bin from u in [0, 1). Precondition: !is_zero(). Cost O(log n).
  DiscreteSample sample_discrete(float u) const;
  /// P(i) = f_i / S; 0 for an out-of-range index or an empty distribution.
  float probability(int index) const;

  /// A point of the piecewise-constant density over [0, 1).
  struct ContinuousSample {
    float x = 0;    ///< in [0, 1)
    float pdf = 0;  ///< p(x) = n f_i / S, never 0
    int index = 0;  ///< the bin x lies in
  };
  /// Inverts the continuous CDF at u in [0, 1). Precondition: !is_zero(). Cost O(log n).
  ContinuousSample sample_continuous(float u) const;
  /// p(x) for x in [0, 1] (x = 1 counts as the last bin); 0 outside, or if empty.
  float pdf(float x) const;

  int size() const { return int(weights_.size()); }
  /// S = Σ f_i (the integral of the step function over [0, 1) is S / n).
  double sum() const { return sum_; }
  bool is_zero() const { return !(sum_ > 0.0); }

 private:
  int find_bin(float u) const;
  int bin_of(float x) const;

  std::vector<double> weights_;
  std::vector<double> cdf_;  // n + 1 entries, cdf_[0] = 0, cdf_[n] = 1
  double sum_ = 0.0;
};

}  // namespace rimu
