// A density over the unit square that is bilinear between values given at the points of a grid, optionally
// conditioned on a few parameters at whose tabulated values the grid was measured. The tables of measured BRDFs
// (Dupuy & Jakob 2018, "An Adaptive Parameterization for Efficient Material Acquisition and Rendering", Sec. 5;
// the RGL database's files) are such grids: a visible-normal distribution per incident direction (θ, φ), spectral
// values per incident direction and wavelength.
//
// Maths. Values d(i, j) ≥ 0 at the width × height grid points x = i/(width − 1), y = j/(height − 1); between them
// d is bilinear. In grid units (a cell is 1 × 1) a row's integral is R(j) = Σᵢ ½(d(i, j) + d(i+1, j)), and the
// whole integral Σⱼ ½(R(j) + R(j+1)), exactly (bilinear functions integrate so). sample() inverts the marginal
// CDF in y, which within a row band is ∫₀ᵗ ((1 − s)R(j) + s R(j+1)) ds — quadratic in t, solved in closed form —
// and then the conditional CDF in x at that t, again a quadratic within the cell. invert() is its exact inverse,
// which the measured BRDF needs to find the sample that led to a given direction.
//
// Parameters. With P parameters (at most 3), each tabulated at increasing values, the table holds one grid per
// combination of tabulated values (the first parameter outermost). For a parameter in between, the grid, its CDFs
// and its density are the multilinear blend of the neighbouring grids (clamped at the ends): blending CDFs and
// values with the same weights keeps sample(), invert() and density() consistent with one another.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "transport/geometry/vector.h"

namespace rimu {

class BilinearWarp2D {
 public:
  static constexpr int kMaxParameters = 3;

  /// What the table is for.
  enum class Use {
    /// A density to sample: each grid is normalised to integrate to 1 over the unit square, CDFs are built.
    warp,
    /// Values to interpolate only (value()): kept as given, no CDFs.
    interpolate,
  };

  /// `values`: for each combination of parameter values (first parameter outermost, last innermost), height rows
  /// of width values (x fastest). `parameter_values[k]`: the values the k-th parameter was tabulated at,
  /// strictly increasing. Preconditions (the reader checks them and says what is wrong): width, height ≥ 2; sizes
  /// consistent; for Use::warp, values finite, ≥ 0 and of positive sum in each grid. Cost O(values).
  BilinearWarp2D(std::span<const float> values, int width, int height,
                 std::vector<std::vector<float>> parameter_values, Use use);
  BilinearWarp2D() = default;

  struct Sample {
    Vec2 p;         ///< in [0, 1]²
    float density;  ///< with respect to dx dy on the unit square
  };

  /// A point with the density of the (blended) grid, from a uniform u. Use::warp only. Cost O(log width + log height).
  Sample sample(Vec2 u, std::span<const float> parameters) const;
  /// The u that sample() maps to p, and the density at p. Use::warp only. Cost O(1).
  Sample invert(Vec2 p, std::span<const float> parameters) const;
  /// The normalised density at p (Use::warp). Cost O(1).
  float density(Vec2 p, std::span<const float> parameters) const;
  /// The bilinearly interpolated value at p, as given (Use::interpolate). Cost O(1).
  float value(Vec2 p, std::span<const float> parameters) const;
  /// value() at one point for four values of the last parameter, the others given in `leading` (one fewer than the
  /// table's parameters): the leading parameters' grids and p's cell are found once, not once per value (a measured
  /// BRDF's spectra at the four wavelengths of a path). Use::interpolate.
  std::array<float, 4> values_along_last(Vec2 p, std::span<const float> leading, const std::array<float, 4>& last) const;

  int width() const { return width_; }
  int height() const { return height_; }
  size_t memory_bytes() const;

 private:
  /// The grids a parameter vector blends and their weights (up to 2^3).
  struct Blend {
    std::array<size_t, 8> grid{};  // index of each blended grid
    std::array<float, 8> weight{};
    int count = 0;
  };
  /// Parameter k's tabulated interval [index, index + 1] holding x and x's weight towards index + 1 (clamped at the
  /// ends; 0 for a NaN x or a parameter tabulated once).
  struct Step {
    int index;
    float weight;
  };
  Step step_along(size_t k, float x) const;
  /// The grid cell holding p (clamped to the square): its corner (x, y), the index of that corner's value in a grid,
  /// and p's position (s, t) within the cell.
  struct Cell {
    int x, y;
    size_t index;
    float s, t;
  };
  Cell locate(Vec2 p) const;
  /// The blend of the first parameters.size() parameters (all of them, or the leading ones).
  Blend blend(std::span<const float> parameters) const;
  /// Σₖ weightₖ · table[gridₖ · per_grid + index]: a table's entry blended over the grids.
  static float blended(const std::vector<float>& table, const Blend& b, size_t per_grid, size_t index);
  float bilinear(Vec2 p, const Blend& b) const;
  /// The density along the cell starting at grid index i, at height t within it: its values at the left (c0) and
  /// right (c1) edges, each interpolated between the cell's two rows. sample() and invert() share it.
  struct CellEdges {
    float c0, c1;
  };
  CellEdges cell_edges(const Blend& b, size_t i, float t) const;

  int width_ = 0, height_ = 0;
  std::vector<std::vector<float>> parameter_values_;
  std::vector<size_t> parameter_stride_;  // in grids
  std::vector<float> values_;             // normalised for Use::warp
  std::vector<float> row_cdf_;            // per grid: height rows of width running integrals (grid units)
  std::vector<float> marginal_cdf_;       // per grid: height running integrals
};

}  // namespace rimu
