#include "transport/sampling/distribution_2d.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace rimu {

namespace {
// Bins per guide cell on average: a search then reads ~16 CDF values, one or two cache lines.
constexpr int kBinsPerGuideCell = 16;
constexpr float kBelowOne = 0x1.fffffep-1f;

// The cell of [0, 1) that x lies in, for `count` equal cells; x = 1 counts as the last.
int cell_of(float x, int count) { return std::clamp(int(x * float(count)), 0, count - 1); }
}  // namespace

int Distribution2D::guide_cells_for(int bins) { return std::max(1, bins / kBinsPerGuideCell); }

Distribution2D::Cdf Distribution2D::row(int y) const {
  const int g = guide_cells_for(width_);
  return {row_cdfs_.data() + size_t(y) * (width_ + 1), row_guides_.data() + size_t(y) * (g + 1), width_, g};
}

Distribution2D::Cdf Distribution2D::marginal() const {
  return {marginal_cdf_.data(), marginal_guide_.data(), height_, guide_cells_for(height_)};
}

template <typename Weight>
double Distribution2D::build(std::span<const Weight> weights, float* cdf, uint32_t* guide, int guide_cells) {
  const int n = int(weights.size());
  // Sums in double, rounded once per entry: rounding is monotone, so the float CDF never decreases, and a bin of
  // zero weight has c_i = c_{i+1} exactly (zero width: never drawn, pdf 0).
  double sum = 0.0;
  for (const Weight weight : weights) {
    const double w = weight;
    assert(std::isfinite(w) && w >= 0.0 && "distribution weights must be finite and >= 0");
    sum += w;
  }
  double running = 0.0;
  cdf[0] = 0.0f;
  for (int i = 0; i < n; ++i) {
    running += weights[i];
    cdf[i + 1] = sum > 0.0 ? float(running / sum) : 0.0f;
  }
  if (sum > 0.0) {
    // Rounding may leave the last sums a few ulps from 1; pin them, and the trailing zero-weight bins with them,
    // so that u < 1 never lands beyond the last positive bin.
    int last_positive = n;
    while (last_positive > 0 && weights[last_positive - 1] == 0.0) --last_positive;
    for (int i = last_positive; i <= n; ++i) cdf[i] = 1.0f;
  }
  // guide[k] = the bin holding u = k/G: the last i with c_i ≤ k/G (one pass, both sequences increase).
  int i = 0;
  for (int k = 0; k <= guide_cells; ++k) {
    const float u = std::min(float(k) / float(guide_cells), kBelowOne);
    while (i + 1 < n && cdf[i + 1] <= u) ++i;
    guide[k] = uint32_t(i);
  }
  return sum;
}

Distribution2D::Distribution2D(std::span<const double> weights, int width, int height)
    : width_(width), height_(height) {
  build_tables(weights);
}

Distribution2D::Distribution2D(std::span<const float> weights, int width, int height)
    : width_(width), height_(height) {
  build_tables(weights);
}

template <typename Weight>
void Distribution2D::build_tables(std::span<const Weight> weights) {
  const int width = width_, height = height_;
  assert(width > 0 && height > 0 && weights.size() == size_t(width) * size_t(height));
  const int row_guide = guide_cells_for(width);
  row_cdfs_.resize(size_t(height) * (width + 1));
  row_guides_.resize(size_t(height) * (row_guide + 1));
  std::vector<double> row_sums(height);
  for (int y = 0; y < height; ++y)
    row_sums[y] = build(weights.subspan(size_t(y) * width, width), row_cdfs_.data() + size_t(y) * (width + 1),
                        row_guides_.data() + size_t(y) * (row_guide + 1), row_guide);
  marginal_cdf_.resize(height + 1);
  marginal_guide_.resize(guide_cells_for(height) + 1);
  total_ = build(std::span<const double>(row_sums), marginal_cdf_.data(), marginal_guide_.data(), guide_cells_for(height));
}

Distribution2D::Found Distribution2D::find(const Cdf& c, float u) {
  u = std::clamp(u, 0.0f, kBelowOne);
  // The guide brackets the answer: bins guide[k] .. guide[k + 1] hold every u in [k/G, (k+1)/G].
  const int k = cell_of(u, c.guide_cells);
  int lo = int(c.guide[k]), hi = int(c.guide[k + 1]);
  // u·G and k/G are rounded: at a guide cell's edge u may belong one bin outside; widen the bracket then (rare).
  while (lo > 0 && c.cdf[lo] > u) --lo;
  while (hi + 1 < c.bins && c.cdf[hi + 1] <= u) ++hi;
  int count = hi - lo + 1;
  // The last i in [lo, lo + count) with c_i ≤ u (c_lo ≤ u holds), by a branch-free binary search.
  while (count > 1) {
    const int half = count / 2;
    lo = c.cdf[lo + half] <= u ? lo + half : lo;
    count -= half;
  }
  // c_lo ≤ u < c_{lo+1}: the strict inequality skips zero-width bins, so the width is positive.
  const float width = c.cdf[lo + 1] - c.cdf[lo];
  return {lo, width, std::clamp((u - c.cdf[lo]) / width, 0.0f, kBelowOne)};
}

Distribution2D::Sample Distribution2D::sample(Vec2 u) const {
  assert(!is_zero());
  const Found y = find(marginal(), u.y);
  const Found x = find(row(y.index), u.x);
  // Float rounding can put (i + offset)/n a hair into a neighbouring cell, whose weight may be zero; nudge the
  // coordinate back so that pdf() reports this cell's density.
  const auto place = [](int i, float offset, int n) {
    float t = std::min((float(i) + offset) / float(n), kBelowOne);
    while (cell_of(t, n) < i) t = std::nextafter(t, 1.0f);
    while (cell_of(t, n) > i) t = std::nextafter(t, 0.0f);
    return t;
  };
  Sample s;
  s.uv = {place(x.index, x.offset, width_), place(y.index, y.offset, height_)};
  s.x = x.index;
  s.y = y.index;
  s.pdf = float(width_) * x.width * float(height_) * y.width;
  return s;
}

float Distribution2D::pdf(Vec2 uv) const {
  if (is_zero() || !(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) return 0.0f;
  const int y = cell_of(uv.y, height_), x = cell_of(uv.x, width_);
  const float* m = marginal_cdf_.data();
  const float* r = row_cdfs_.data() + size_t(y) * (width_ + 1);
  return float(width_) * (r[x + 1] - r[x]) * float(height_) * (m[y + 1] - m[y]);
}

size_t Distribution2D::memory_bytes() const {
  return (row_cdfs_.size() + marginal_cdf_.size()) * sizeof(float) +
         (row_guides_.size() + marginal_guide_.size()) * sizeof(uint32_t);
}

}  // namespace rimu
