#include "transport/sampling/bilinear_warp_2d.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace rimu {

namespace {

// The interval [k, k + 1] of 0..n−1 with pred(k) true and pred(k + 1) false, for a predicate that is true up to
// some index and false after it; clamped to 0..n−2 (below the first entry: 0; past the last: n − 2).
template <typename Predicate>
int interval_of(int n, Predicate pred) {
  int first = 1, count = n - 2;  // search 1..n−2 for the first index whose predicate is false
  while (count > 0) {
    const int half = count / 2, middle = first + half;
    if (pred(middle)) {
      first = middle + 1;
      count -= half + 1;
    } else {
      count = half;
    }
  }
  return std::clamp(first - 1, 0, n - 2);
}

// t in [0, 1] with ∫₀ᵗ ((1 − s)a + s b) ds = c: the inverse of a linear density's CDF over a unit interval.
// Nearly constant densities use the linear solution, which the quadratic's formula loses to cancellation.
float invert_linear_cdf(float a, float b, float c) {
  const float sum = a + b;
  if (!(sum > 0.0f)) return 0.5f;  // a band without mass is never drawn; any point keeps the result finite
  if (std::fabs(a - b) < 1e-4f * sum) return std::clamp(2.0f * c / sum, 0.0f, 1.0f);
  const float t = (a - std::sqrt(std::max(0.0f, a * a - 2.0f * c * (a - b)))) / (a - b);
  return std::clamp(t, 0.0f, 1.0f);
}

constexpr float kSampleEpsilon = 0x1p-24f;

// A coordinate clamped to [0, 1]; NaN (from a direction that was not finite) reads as 0, so that a lookup stays
// inside the table.
float unit(float x) { return x >= 0.0f ? std::min(x, 1.0f) : 0.0f; }

}  // namespace

BilinearWarp2D::BilinearWarp2D(std::span<const float> values, int width, int height,
                               std::vector<std::vector<float>> parameter_values, Use use)
    : width_(width), height_(height), parameter_values_(std::move(parameter_values)) {
  assert(width >= 2 && height >= 2 && parameter_values_.size() <= size_t(kMaxParameters));
  // The last parameter varies fastest; a parameter tabulated at one value contributes stride 0 (it is ignored).
  size_t grids = 1;
  parameter_stride_.assign(parameter_values_.size(), 0);
  for (int k = int(parameter_values_.size()) - 1; k >= 0; --k) {
    const size_t n = parameter_values_[size_t(k)].size();
    assert(n >= 1);
    parameter_stride_[size_t(k)] = n > 1 ? grids : 0;
    grids *= n;
  }
  const size_t per_grid = size_t(width) * size_t(height);
  assert(values.size() == grids * per_grid);
  values_.assign(values.begin(), values.end());
  if (use == Use::interpolate) return;

  row_cdf_.resize(values_.size());
  marginal_cdf_.resize(grids * size_t(height));
  for (size_t g = 0; g < grids; ++g) {
    float* v = values_.data() + g * per_grid;
    float* rows = row_cdf_.data() + g * per_grid;
    float* marginal = marginal_cdf_.data() + g * size_t(height);
    // Running integrals in double: a row of thousands of values keeps its last bits.
    for (int y = 0; y < height; ++y) {
      double sum = 0.0;
      const size_t row = size_t(y) * size_t(width);
      rows[row] = 0.0f;
      for (int x = 0; x + 1 < width; ++x) {
        sum += 0.5 * (double(v[row + size_t(x)]) + double(v[row + size_t(x) + 1]));
        rows[row + size_t(x) + 1] = float(sum);
      }
    }
    double sum = 0.0;
    marginal[0] = 0.0f;
    for (int y = 0; y + 1 < height; ++y) {
      sum += 0.5 * (double(rows[size_t(y + 1) * size_t(width) - 1]) + double(rows[size_t(y + 2) * size_t(width) - 1]));
      marginal[y + 1] = float(sum);
    }
    assert(sum > 0.0);
    const float normalisation = float(1.0 / sum);
    for (size_t i = 0; i < per_grid; ++i) {
      v[i] *= normalisation;
      rows[i] *= normalisation;
    }
    for (int y = 0; y < height; ++y) marginal[y] *= normalisation;
  }
}

BilinearWarp2D::Step BilinearWarp2D::step_along(size_t k, float x) const {
  const std::vector<float>& tabulated = parameter_values_[k];
  if (tabulated.size() < 2) return {0, 0.0f};
  const int i = interval_of(int(tabulated.size()), [&](int j) { return tabulated[size_t(j)] <= x; });
  const float t = std::clamp((x - tabulated[size_t(i)]) / (tabulated[size_t(i) + 1] - tabulated[size_t(i)]), 0.0f, 1.0f);
  return {i, std::isfinite(t) ? t : 0.0f};  // a NaN parameter takes the first grid rather than spreading NaN
}

BilinearWarp2D::Cell BilinearWarp2D::locate(Vec2 p) const {
  const float gx = unit(p.x) * float(width_ - 1), gy = unit(p.y) * float(height_ - 1);
  const int x = std::min(int(gx), width_ - 2), y = std::min(int(gy), height_ - 2);
  return {x, y, size_t(y) * size_t(width_) + size_t(x), gx - float(x), gy - float(y)};
}

BilinearWarp2D::Blend BilinearWarp2D::blend(std::span<const float> parameters) const {
  assert(parameters.size() <= parameter_values_.size());
  Blend b;
  b.grid[0] = 0;
  b.weight[0] = 1.0f;
  b.count = 1;
  for (size_t k = 0; k < parameters.size(); ++k) {
    if (parameter_values_[k].size() < 2) continue;
    const auto [i, w] = step_along(k, parameters[k]);
    // Each grid so far splits into its neighbour below (1 − w) and above (w) along this parameter.
    for (int c = b.count - 1; c >= 0; --c) {
      const size_t base = b.grid[size_t(c)] + size_t(i) * parameter_stride_[k];
      const float weight = b.weight[size_t(c)];
      b.grid[size_t(2 * c)] = base;
      b.weight[size_t(2 * c)] = weight * (1.0f - w);
      b.grid[size_t(2 * c + 1)] = base + parameter_stride_[k];
      b.weight[size_t(2 * c + 1)] = weight * w;
    }
    b.count *= 2;
  }
  return b;
}

float BilinearWarp2D::blended(const std::vector<float>& table, const Blend& b, size_t per_grid, size_t index) {
  float sum = 0.0f;
  for (int c = 0; c < b.count; ++c) sum += b.weight[size_t(c)] * table[b.grid[size_t(c)] * per_grid + index];
  return sum;
}

float BilinearWarp2D::bilinear(Vec2 p, const Blend& b) const {
  const auto [x, y, i, s, t] = locate(p);
  const size_t per_grid = size_t(width_) * size_t(height_);
  const float v00 = blended(values_, b, per_grid, i), v10 = blended(values_, b, per_grid, i + 1);
  const float v01 = blended(values_, b, per_grid, i + size_t(width_)), v11 = blended(values_, b, per_grid, i + size_t(width_) + 1);
  return (1.0f - t) * ((1.0f - s) * v00 + s * v10) + t * ((1.0f - s) * v01 + s * v11);
}

float BilinearWarp2D::value(Vec2 p, std::span<const float> parameters) const { return bilinear(p, blend(parameters)); }

std::array<float, 4> BilinearWarp2D::values_along_last(Vec2 p, std::span<const float> leading,
                                                      const std::array<float, 4>& last) const {
  assert(leading.size() + 1 == parameter_values_.size());
  const Blend b = blend(leading);
  const Cell cell = locate(p);
  const size_t per_grid = size_t(width_) * size_t(height_), w = size_t(width_);
  // The grid g's bilinear value at p.
  const auto at = [&](size_t g) {
    const float* v = values_.data() + g * per_grid + cell.index;
    const float s = cell.s, t = cell.t;
    return (1.0f - t) * ((1.0f - s) * v[0] + s * v[1]) + t * ((1.0f - s) * v[w] + s * v[w + 1]);
  };
  const size_t stride = parameter_stride_.back();
  std::array<float, 4> out{};
  for (size_t lane = 0; lane < 4; ++lane) {
    const auto [i, weight] = step_along(parameter_values_.size() - 1, last[lane]);
    float sum = 0.0f;
    for (int c = 0; c < b.count; ++c) {
      const size_t g = b.grid[size_t(c)] + size_t(i) * stride;
      sum += b.weight[size_t(c)] * ((1.0f - weight) * at(g) + (weight > 0.0f ? weight * at(g + stride) : 0.0f));
    }
    out[lane] = sum;
  }
  return out;
}

float BilinearWarp2D::density(Vec2 p, std::span<const float> parameters) const {
  // Normalised in grid units; a unit-square area is (width − 1)(height − 1) grid cells.
  return bilinear(p, blend(parameters)) * float(width_ - 1) * float(height_ - 1);
}

BilinearWarp2D::CellEdges BilinearWarp2D::cell_edges(const Blend& b, size_t i, float t) const {
  const size_t per_grid = size_t(width_) * size_t(height_), w = size_t(width_);
  return {(1.0f - t) * blended(values_, b, per_grid, i) + t * blended(values_, b, per_grid, i + w),
          (1.0f - t) * blended(values_, b, per_grid, i + 1) + t * blended(values_, b, per_grid, i + w + 1)};
}

BilinearWarp2D::Sample BilinearWarp2D::sample(Vec2 u, std::span<const float> parameters) const {
  assert(!marginal_cdf_.empty());
  const Blend b = blend(parameters);
  const size_t per_grid = size_t(width_) * size_t(height_), w = size_t(width_);
  u.x = std::clamp(unit(u.x), kSampleEpsilon, 1.0f - kSampleEpsilon);
  u.y = std::clamp(unit(u.y), kSampleEpsilon, 1.0f - kSampleEpsilon);

  // The row band: the marginal CDF's interval that holds u.y, then t within it.
  const auto marginal = [&](int y) { return blended(marginal_cdf_, b, size_t(height_), size_t(y)); };
  const int y = interval_of(height_, [&](int j) { return marginal(j) < u.y; });
  const float row0 = blended(row_cdf_, b, per_grid, size_t(y) * w + w - 1);
  const float row1 = blended(row_cdf_, b, per_grid, size_t(y + 1) * w + w - 1);
  const float t = invert_linear_cdf(row0, row1, u.y - marginal(y));

  // The column within the row at t: its running integral is the blend of the two rows' at t.
  const float target = u.x * ((1.0f - t) * row0 + t * row1);
  const auto running = [&](int x) {
    return (1.0f - t) * blended(row_cdf_, b, per_grid, size_t(y) * w + size_t(x)) +
           t * blended(row_cdf_, b, per_grid, size_t(y + 1) * w + size_t(x));
  };
  const int x = interval_of(width_, [&](int i) { return running(i) < target; });
  const size_t i = size_t(y) * w + size_t(x);
  const auto [c0, c1] = cell_edges(b, i, t);
  const float s = invert_linear_cdf(c0, c1, target - running(x));

  const float cells = float(width_ - 1) * float(height_ - 1);
  return {{(float(x) + s) / float(width_ - 1), (float(y) + t) / float(height_ - 1)}, ((1.0f - s) * c0 + s * c1) * cells};
}

BilinearWarp2D::Sample BilinearWarp2D::invert(Vec2 p, std::span<const float> parameters) const {
  assert(!marginal_cdf_.empty());
  const Blend b = blend(parameters);
  const size_t per_grid = size_t(width_) * size_t(height_), w = size_t(width_);
  const auto [x, y, i, s, t] = locate(p);

  const auto [c0, c1] = cell_edges(b, i, t);
  const float row0 = blended(row_cdf_, b, per_grid, size_t(y) * w + w - 1);
  const float row1 = blended(row_cdf_, b, per_grid, size_t(y + 1) * w + w - 1);
  const float running = (1.0f - t) * blended(row_cdf_, b, per_grid, i) + t * blended(row_cdf_, b, per_grid, i + w);
  const float row_total = (1.0f - t) * row0 + t * row1;
  // The CDFs sample() inverted, evaluated forwards: within the cell ∫₀ˢ ((1 − σ)c0 + σ c1) dσ = s(c0 + s(c1 − c0)/2).
  const float ux = row_total > 0.0f ? (running + s * (c0 + 0.5f * s * (c1 - c0))) / row_total : 0.0f;
  const float uy = blended(marginal_cdf_, b, size_t(height_), size_t(y)) + t * (row0 + 0.5f * t * (row1 - row0));

  const float cells = float(width_ - 1) * float(height_ - 1);
  return {{ux, uy}, ((1.0f - s) * c0 + s * c1) * cells};
}

size_t BilinearWarp2D::memory_bytes() const {
  size_t bytes = sizeof(float) * (values_.size() + row_cdf_.size() + marginal_cdf_.size());
  for (const auto& v : parameter_values_) bytes += sizeof(float) * v.size();
  return bytes;
}

}  // namespace rimu
