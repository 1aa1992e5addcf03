// 3x3 matrices for colour-space and chromatic-adaptation transforms (double precision: these are derived once).
#pragma once

#include <array>

#include "spectral/colorimetry/chromaticity.h"

namespace rimu {

/// Row-major 3x3 matrix acting on column vectors.
struct Matrix3 {
  std::array<std::array<double, 3>, 3> m{};

  static Matrix3 identity() { return {{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}; }
  static Matrix3 diagonal(double a, double b, double c) { return {{{{a, 0, 0}, {0, b, 0}, {0, 0, c}}}}; }

  double operator()(int row, int column) const { return m[row][column]; }
  double& operator()(int row, int column) { return m[row][column]; }

  friend Matrix3 operator*(const Matrix3& a, const Matrix3& b) {
    Matrix3 out;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    return out;
  }
  /// Applies the matrix to a 3-vector.
  std::array<double, 3> apply(const std::array<double, 3>& v) const {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
  }
  Xyz apply(const Xyz& v) const {
    const auto r = apply(std::array<double, 3>{v.x, v.y, v.z});
    return {r[0], r[1], r[2]};
  }
  double determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  /// The inverse (cofactors / determinant). The caller guarantees the matrix is invertible (asserted).
  Matrix3 inverse() const;
};

}  // namespace rimu
