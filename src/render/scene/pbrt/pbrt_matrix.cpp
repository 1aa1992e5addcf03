#include "render/scene/pbrt/pbrt_matrix.h"
#include "render/scene/pbrt/pbrt_vector_math.h"

#include <cmath>
#include <numbers>

namespace rimu {

namespace {

using V3 = std::array<double, 3>;
using pbrt_math::cross;
using pbrt_math::length;
using pbrt_math::normalized;

}  // namespace

PbrtMatrix PbrtMatrix::identity() {
  PbrtMatrix r;
  for (int i = 0; i < 4; ++i) r.m[i][i] = 1.0;
  return r;
}

PbrtMatrix PbrtMatrix::translate(double x, double y, double z) {
  PbrtMatrix r = identity();
  r.m[0][3] = x;
  r.m[1][3] = y;
  r.m[2][3] = z;
  return r;
}

PbrtMatrix PbrtMatrix::scale(double x, double y, double z) {
  PbrtMatrix r = identity();
  r.m[0][0] = x;
  r.m[1][1] = y;
  r.m[2][2] = z;
  return r;
}

PbrtMatrix PbrtMatrix::rotate(double angle_deg, double x, double y, double z) {
  // Rodrigues' formula: R = cos θ I + sin θ [a]× + (1 − cos θ) a aᵀ for the unit axis a.
  const V3 a = normalized({x, y, z});
  const double theta = angle_deg * std::numbers::pi / 180.0;
  const double c = std::cos(theta), s = std::sin(theta), t = 1.0 - c;
  PbrtMatrix r = identity();
  r.m[0] = {c + t * a[0] * a[0], t * a[0] * a[1] - s * a[2], t * a[0] * a[2] + s * a[1], 0};
  r.m[1] = {t * a[0] * a[1] + s * a[2], c + t * a[1] * a[1], t * a[1] * a[2] - s * a[0], 0};
  r.m[2] = {t * a[0] * a[2] - s * a[1], t * a[1] * a[2] + s * a[0], c + t * a[2] * a[2], 0};
  return r;
}

std::optional<PbrtMatrix> PbrtMatrix::look_at(const V3& eye, const V3& look, const V3& up) {
  const V3 d = {look[0] - eye[0], look[1] - eye[1], look[2] - eye[2]};
  if (length(d) == 0.0 || length(up) == 0.0) return std::nullopt;
  const V3 dir = normalized(d);
  const V3 right_raw = cross(normalized(up), dir);
  if (length(right_raw) < 1e-12) return std::nullopt;
  const V3 right = normalized(right_raw);
  const V3 new_up = cross(dir, right);
  PbrtMatrix world_from_camera = identity();
  for (int i = 0; i < 3; ++i) {
    world_from_camera.m[i][0] = right[i];
    world_from_camera.m[i][1] = new_up[i];
    world_from_camera.m[i][2] = dir[i];
    world_from_camera.m[i][3] = eye[i];
  }
  return world_from_camera.inverse();
}

PbrtMatrix PbrtMatrix::from_pbrt_numbers(const double* sixteen) {
  PbrtMatrix r;
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) r.m[row][column] = sixteen[column * 4 + row];
  return r;
}

PbrtMatrix PbrtMatrix::operator*(const PbrtMatrix& o) const {
  PbrtMatrix r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) sum += m[i][k] * o.m[k][j];
      r.m[i][j] = sum;
    }
  return r;
}

V3 PbrtMatrix::point(const V3& p) const {
  V3 r;
  for (int i = 0; i < 3; ++i) r[i] = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
  return r;
}

V3 PbrtMatrix::vector(const V3& v) const {
  V3 r;
  for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
  return r;
}

double PbrtMatrix::determinant3() const {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

std::optional<PbrtMatrix> PbrtMatrix::inverse() const {
  // Gauss-Jordan elimination with partial pivoting on [M | I].
  std::array<std::array<double, 8>, 4> a{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) a[i][j] = m[i][j];
    a[i][4 + i] = 1.0;
  }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (!(std::abs(a[pivot][col]) > 1e-300)) return std::nullopt;
    std::swap(a[col], a[pivot]);
    const double p = a[col][col];
    for (double& v : a[col]) v /= p;
    for (int r = 0; r < 4; ++r)
      if (r != col) {
        const double f = a[r][col];
        for (int j = 0; j < 8; ++j) a[r][j] -= f * a[col][j];
      }
  }
  PbrtMatrix r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a[i][4 + j];
  if (!r.is_finite()) return std::nullopt;
  return r;
}

bool PbrtMatrix::is_affine() const { return m[3][0] == 0 && m[3][1] == 0 && m[3][2] == 0 && m[3][3] == 1; }

bool PbrtMatrix::is_identity() const {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (m[i][j] != (i == j ? 1.0 : 0.0)) return false;
  return true;
}

bool PbrtMatrix::is_finite() const {
  for (const auto& row : m)
    for (double v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace rimu
