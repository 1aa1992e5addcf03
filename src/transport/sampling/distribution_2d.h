// A piecewise-constant density over the unit square [0, 1)², sampled by inverting a marginal and a conditional
// CDF. The environment light uses it over its image (u across, v down).
//
// Maths. Weights f(x, y) ≥ 0 on a width × height grid (row y covers v in [y/h, (y+1)/h), column x covers u in
// [x/w, (x+1)/w)). With S = Σ f, the density is p(u, v) = w·h·f(x, y) / S. It factors as
//   p(v) = h · Σ_x f(x, y) / S          (the marginal over rows: Distribution1D of the row sums), and
//   p(u | v) = w · f(x, y) / Σ_x f(x, y)  (the conditional in row y: Distribution1D of that row),
// and p(u, v) = p(v) · p(u | v). Sampling draws v from the marginal with u.y, then u from row y with u.x.
#pragma once

#include <span>
#include <vector>

#include "transport/sampling/distribution_1d.h"
#include "transport/geometry/vector.h"

namespace rimu {

class Distribution2D {
 public:
  /// `weights` holds width × height non-negative values, row by row (index y·width + x). Cost O(width·height).
  Distribution2D(std::span<const double> weights, int width, int height);
  Distribution2D() = default;

  struct Sample {
    Vec2 uv;              ///< in [0, 1)²
    float pdf = 0;        ///< p(u, v) with respect to du dv, never 0
    int x = 0, y = 0;     ///< the cell uv lies in
  };
  /// A point with density p(u, v) from two uniform numbers. Precondition: !is_zero(). Cost O(log w + log h).
  Sample sample(Vec2 u) const;
  /// p(u, v) for uv in [0, 1]²; 0 outside or if all weights are zero.
  float pdf(Vec2 uv) const;

  bool is_zero() const { return marginal_.is_zero(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  std::vector<Distribution1D> conditional_;  // one per row
  Distribution1D marginal_;                  // over rows
  int width_ = 0, height_ = 0;
};

}  // namespace rimu
