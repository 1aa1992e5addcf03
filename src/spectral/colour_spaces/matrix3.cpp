#include "spectral/colour_spaces/matrix3.h"

#include <cassert>
#include <cmath>

namespace rimu {

Matrix3 Matrix3::inverse() const {
  const double det = determinant();
  assert(std::abs(det) > 0.0 && "Matrix3::inverse of a singular matrix");
  const double s = 1.0 / det;
  Matrix3 r;
  r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * s;
  r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * s;
  r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * s;
  r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * s;
  r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * s;
  r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * s;
  r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * s;
  r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * s;
  r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * s;
  return r;
}

}  // namespace rimu
