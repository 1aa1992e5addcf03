#include "render/film/piecewise_linear_distribution.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace rimu {

PiecewiseLinearDistribution::PiecewiseLinearDistribution(double lo, double hi, std::vector<double> knot_values)
    : lo_(lo), hi_(hi), f_(std::move(knot_values)) {
  if (f_.size() < 2 || !(hi > lo)) throw std::invalid_argument("piecewise-linear distribution needs two knots");
  for (double v : f_)
    if (!(v >= 0.0) || !std::isfinite(v)) throw std::invalid_argument("piecewise-linear values must be finite and >= 0");
  step_ = (hi - lo) / double(f_.size() - 1);
  cdf_.resize(f_.size(), 0.0);
  for (size_t i = 1; i < f_.size(); ++i) cdf_[i] = cdf_[i - 1] + 0.5 * step_ * (f_[i - 1] + f_[i]);
  integral_ = cdf_.back();
  if (!(integral_ > 0.0)) throw std::invalid_argument("piecewise-linear distribution has zero integral");
  guide_.resize(f_.size());
  for (size_t j = 0; j < guide_.size(); ++j) {
    const double target = integral_ * double(j) / double(guide_.size());
    guide_[j] = unsigned(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
  }
}

double PiecewiseLinearDistribution::sample(double u) const {
  const double target = u * integral_;
  // The segment [i, i+1] with cdf_[i] <= target < cdf_[i+1]; zero-area segments are never chosen.
  // The index upper_bound(cdf_, target) would return, found from the guide: start at or before it, step forward
  // past every knot whose CDF is ≤ target (stepping back first guards the bucket index against rounding).
  const size_t n = cdf_.size();
  const double scaled = u * double(guide_.size());
  size_t i = guide_[std::min(guide_.size() - 1, size_t(std::max(0.0, scaled)))];
  while (i > 0 && cdf_[i - 1] > target) --i;
  while (i < n && cdf_[i] <= target) ++i;
  i = std::clamp<size_t>(i, 1, f_.size() - 1) - 1;
  while (i + 1 < f_.size() - 1 && cdf_[i + 1] == cdf_[i]) ++i;
  // Within the segment, with t ∈ [0, 1] and a = f_i, b = f_{i+1}, the area up to t is h(a t + (b − a) t²/2) = s.
  // Its root t = 2s' / (a + √(a² + 2(b − a)s')) with s' = s/h is the quadratic formula multiplied through by its
  // conjugate: stable when b ≈ a (no division by b − a) and when a = 0.
  const double a = f_[i], b = f_[i + 1];
  const double s = std::max(0.0, target - cdf_[i]) / step_;
  const double root = std::sqrt(std::max(0.0, a * a + 2.0 * (b - a) * s));
  const double denominator = a + root;
  const double t = denominator > 0.0 ? std::clamp(2.0 * s / denominator, 0.0, 1.0) : 0.0;
  return std::min(hi_, lo_ + (double(i) + t) * step_);
}

double PiecewiseLinearDistribution::pdf(double x) const {
  if (!(x >= lo_ && x <= hi_)) return 0.0;
  const double position = (x - lo_) / step_;
  const size_t i = std::min(size_t(position), f_.size() - 2);
  const double t = position - double(i);
  return (f_[i] + t * (f_[i + 1] - f_[i])) / integral_;
}

}  // namespace rimu
