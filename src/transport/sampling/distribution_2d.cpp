#include "transport/sampling/distribution_2d.h"

#include <algorithm>
#include <cassert>

namespace rimu {

Distribution2D::Distribution2D(std::span<const double> weights, int width, int height)
    : width_(width), height_(height) {
  assert(width > 0 && height > 0 && weights.size() == size_t(width) * size_t(height));
  conditional_.reserve(height);
  std::vector<double> row_sums(height);
  for (int y = 0; y < height; ++y) {
    conditional_.emplace_back(weights.subspan(size_t(y) * width, width));
    row_sums[y] = conditional_.back().sum();
  }
  marginal_ = Distribution1D(row_sums);
}

Distribution2D::Sample Distribution2D::sample(Vec2 u) const {
  const auto v = marginal_.sample_continuous(u.y);
  // The marginal never picks a row of zero sum, so the conditional is non-empty.
  const auto x = conditional_[v.index].sample_continuous(u.x);
  return {{x.x, v.x}, v.pdf * x.pdf, x.index, v.index};
}

float Distribution2D::pdf(Vec2 uv) const {
  if (is_zero() || !(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) return 0.0f;
  const int y = std::clamp(int(uv.y * float(height_)), 0, height_ - 1);
  return marginal_.pdf(uv.y) * conditional_[y].pdf(uv.x);
}

}  // namespace rimu
