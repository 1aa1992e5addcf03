// Chi-square tests of samplers whose samples map to the unit square (the equal-area square of the sphere, an
// environment's or a sky's (u, v)): the expected count of every cell of a grid over the square, and the cell a
// sample falls in. Judged with test::pearson_chi_square from tests/statistics.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "transport/geometry/vector.h"

namespace rimu::test {

/// Expected counts of `draws` samples in the cells_x × cells_y cells of the unit square (row-major, y outer), for
/// samples whose density on the square is `density_square(Vec2)` (for directions on the equal-area square,
/// pdf(direction) · 4π). A cell's probability is the midpoint rule on a sub × sub grid inside it: exact wherever
/// the density is constant on the sub-cells (a tree's leaves, an image's pixels no smaller than a sub-cell).
template <typename Density>
std::vector<double> square_expected_counts(Density&& density_square, int cells_x, int cells_y, int sub, double draws) {
  const int points_x = cells_x * sub, points_y = cells_y * sub;
  std::vector<double> expected(size_t(cells_x) * size_t(cells_y), 0.0);
  for (int cy = 0; cy < cells_y; ++cy)
    for (int cx = 0; cx < cells_x; ++cx) {
      double integral = 0.0;
      for (int sy = 0; sy < sub; ++sy)
        for (int sx = 0; sx < sub; ++sx)
          integral += double(density_square(Vec2{(float(cx * sub + sx) + 0.5f) / float(points_x),
                                                 (float(cy * sub + sy) + 0.5f) / float(points_y)}));
      expected[size_t(cy) * size_t(cells_x) + size_t(cx)] = draws * integral / (double(points_x) * double(points_y));
    }
  return expected;
}

/// The square grid of square_expected_counts(density, cells, cells, sub, draws).
template <typename Density>
std::vector<double> square_expected_counts(Density&& density_square, int cells, int sub, double draws) {
  return square_expected_counts(density_square, cells, cells, sub, draws);
}

/// The row-major index of the cell of the cells_x × cells_y grid that holds `p` in [0, 1]²; the far edges (1)
/// belong to the last row and column.
inline size_t square_cell(Vec2 p, int cells_x, int cells_y) {
  const int cx = std::min(int(p.x * float(cells_x)), cells_x - 1), cy = std::min(int(p.y * float(cells_y)), cells_y - 1);
  return size_t(cy) * size_t(cells_x) + size_t(cx);
}

inline size_t square_cell(Vec2 p, int cells) { return square_cell(p, cells, cells); }

}  // namespace rimu::test
