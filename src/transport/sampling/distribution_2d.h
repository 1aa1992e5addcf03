// A piecewise-constant density over the unit square [0, 1)², sampled by inverting a marginal and a conditional
// CDF. The environment light uses it over its image (u across, v down), the sky and goniometric lights over their
// direction tables.
//
// Maths. Weights f(x, y) ≥ 0 on a width × height grid (row y covers v in [y/h, (y+1)/h), column x covers u in
// [x/w, (x+1)/w)). With S = Σ f, the density is p(u, v) = w·h·f(x, y) / S. It factors as
//   p(v) = h · Σ_x f(x, y) / S          (the marginal over rows), and
//   p(u | v) = w · f(x, y) / Σ_x f(x, y)  (the conditional in row y),
// and p(u, v) = p(v) · p(u | v). Sampling draws v from the marginal with u.y, then u from row y with u.x.
//
// Storage and speed. An environment map of 2048² pixels is 4 M cells, and every light sample of a path visits a
// random row, so the tables are what a sample costs: the CDFs are kept in float (4 B per cell; the double weights
// and CDFs of Distribution1D took 16 B, 64 MiB for such a map, and a sample cost ~130 ns of cache misses), and each
// CDF has a guide table (Chen & Asau 1974's cutpoint method: for k = 0..G the bin holding u = k/G), so a search
// looks at ~16 neighbouring entries instead of a binary search over the row (measured: 2048² map, random u,
// 126–170 → ~30 ns per sample; pdf 50–80 → ~15 ns).
//
// The densities are the float CDF's own: p(u | v) = w (c_{x+1} − c_x) and p(v) = h (C_{y+1} − C_y), the densities
// of what sample() draws, so sampling and pdf() agree to the last bit of the tables. A cell's share of its row (a
// row's of the total) is thus known to ±2⁻²⁴ absolute: relative error 2⁻²⁴/share, and a cell with a share below
// ~6e-8 may round to zero width (never drawn, pdf 0 — consistent, so MIS stays unbiased; the BSDF side finds such
// a cell). The double tables were no better there in practice: u itself comes in steps of 2⁻²⁴ (24-bit samplers),
// so a bin narrower than that was drawn with probability 0 or 2⁻²⁴, not its share. pbrt-v4 keeps float tables too.
// Distribution1D keeps double for its million-bin users (discrete choices, where u_remapped matters).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "transport/geometry/vector.h"

namespace rimu {

class Distribution2D {
 public:
  /// `weights` holds width × height non-negative, finite values, row by row (index y·width + x).
  /// Cost O(width·height).
  Distribution2D(std::span<const double> weights, int width, int height);
  /// The same from float weights: an environment image's millions of weights in half the memory (sums are still
  /// taken in double).
  Distribution2D(std::span<const float> weights, int width, int height);
  Distribution2D() = default;

  struct Sample {
    Vec2 uv;              ///< in [0, 1)²
    float pdf = 0;        ///< p(u, v) with respect to du dv, never 0
    int x = 0, y = 0;     ///< the cell uv lies in
  };
  /// A point with density p(u, v) from two uniform numbers. Precondition: !is_zero(). Cost O(1) expected.
  Sample sample(Vec2 u) const;
  /// p(u, v) for uv in [0, 1]²; 0 outside or if all weights are zero.
  float pdf(Vec2 uv) const;

  bool is_zero() const { return !(total_ > 0.0); }
  int width() const { return width_; }
  int height() const { return height_; }
  /// Bytes held by the tables.
  size_t memory_bytes() const;

 private:
  /// One cumulative distribution over n bins: n + 1 CDF values (c_0 = 0, c_n = 1) and G + 1 guide entries.
  struct Cdf {
    const float* cdf;
    const uint32_t* guide;
    int bins, guide_cells;
  };
  Cdf row(int y) const;
  Cdf marginal() const;
  /// The bin i with c_i ≤ u < c_{i+1} (u in [0, 1)), its width c_{i+1} − c_i > 0 and u's offset in it in [0, 1).
  struct Found {
    int index;
    float width, offset;
  };
  static Found find(const Cdf& c, float u);
  /// Writes the normalised float CDF of `weights` into cdf[0..n] and its guide into guide[0..G]; returns Σ weights.
  template <typename Weight>
  static double build(std::span<const Weight> weights, float* cdf, uint32_t* guide, int guide_cells);
  template <typename Weight>
  void build_tables(std::span<const Weight> weights);
  static int guide_cells_for(int bins);

  std::vector<float> row_cdfs_;         // height × (width + 1)
  std::vector<uint32_t> row_guides_;    // height × (row guide cells + 1)
  std::vector<float> marginal_cdf_;     // height + 1
  std::vector<uint32_t> marginal_guide_;
  double total_ = 0.0;
  int width_ = 0, height_ = 0;
};

}  // namespace rimu
