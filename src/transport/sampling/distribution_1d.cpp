#include "transport/sampling/distribution_1d.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace rimu {

Distribution1D::Distribution1D(std::span<const double> weights) : weights_(weights.begin(), weights.end()) {
  cdf_.resize(weights_.size() + 1, 0.0);
  for (size_t i = 0; i < weights_.size(); ++i) {
    assert(std::isfinite(weights_[i]) && weights_[i] >= 0.0 && "distribution weights must be finite and >= 0");
    cdf_[i + 1] = cdf_[i] + weights_[i];
  }
  sum_ = cdf_.back();
  if (is_zero()) return;
  for (double& c : cdf_) c /= sum_;
  // Rounding may leave the last sum a few ulps from 1; pin it, and the trailing zero-weight bins with it, so that
  // u < 1 can never land beyond the last positive bin.
  size_t last_positive = weights_.size();
  while (last_positive > 0 && weights_[last_positive - 1] == 0.0) --last_positive;
  for (size_t i = last_positive; i <= weights_.size(); ++i) cdf_[i] = 1.0;
}

int Distribution1D::bin_of(float x) const { return std::clamp(int(x * float(size())), 0, size() - 1); }

int Distribution1D::find_bin(float u) const {
  assert(!is_zero());
  // The first c_{i+1} > u; then c_i ≤ u < c_{i+1}, so bin i has positive weight.
  const double u_d = std::clamp(double(u), 0.0, std::nextafter(1.0, 0.0));
  const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), u_d);
  return int(it - cdf_.begin()) - 1;
}

Distribution1D::DiscreteSample Distribution1D::sample_discrete(float u) const {
  const int i = find_bin(u);
  const double width = cdf_[i + 1] - cdf_[i];
  DiscreteSample s;
  s.index = i;
  s.probability = float(weights_[i] / sum_);
  // (u − c_i) / (c_{i+1} − c_i) lies in [0, 1); float rounding of the quotient could reach 1, so clamp below it.
  s.u_remapped = std::min(float((double(u) - cdf_[i]) / width), std::nextafter(1.0f, 0.0f));
  s.u_remapped = std::max(s.u_remapped, 0.0f);
  return s;
}

float Distribution1D::probability(int index) const {
  if (is_zero() || index < 0 || index >= size()) return 0.0f;
  return float(weights_[index] / sum_);
}

Distribution1D::ContinuousSample Distribution1D::sample_continuous(float u) const {
  const int i = find_bin(u);
  const double width = cdf_[i + 1] - cdf_[i];
  const double offset = std::clamp((double(u) - cdf_[i]) / width, 0.0, 1.0);
  ContinuousSample s;
  s.index = i;
  // Float rounding can put (i + offset)/n a hair into a neighbouring bin, whose weight may be zero; nudge x back so
  // that pdf(x) reports this bin's density.
  float x = std::min(float((i + offset) / size()), std::nextafter(1.0f, 0.0f));
  while (bin_of(x) < i) x = std::nextafter(x, 1.0f);
  while (bin_of(x) > i) x = std::nextafter(x, 0.0f);
  s.x = x;
  s.pdf = float(weights_[i] * size() / sum_);
  return s;
}

float Distribution1D::pdf(float x) const {
  if (is_zero() || !(x >= 0.0f && x <= 1.0f)) return 0.0f;
  const int i = bin_of(x);
  return float(weights_[i] * size() / sum_);
}

}  // namespace rimu
