#include "transport/geometry/transform.h"

#include <cmath>

namespace rimu {
namespace {

using Rows = std::array<float, 12>;

Rows multiply(const Rows& a, const Rows& b) {
  Rows r{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      float v = a[i * 4 + 0] * b[0 * 4 + j] + a[i * 4 + 1] * b[1 * 4 + j] + a[i * 4 + 2] * b[2 * 4 + j];
      if (j == 3) v += a[i * 4 + 3];
      r[i * 4 + j] = v;
    }
  }
  return r;
}

// Inverse of an affine 3x4 matrix in double precision; false if the linear part is singular.
bool invert(const Rows& m, Rows& out) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
  const double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  if (!(std::fabs(det) > 1e-30) || !std::isfinite(det)) return false;
  const double s = 1.0 / det;
  const double r[9] = {(e * i - f * h) * s, (c * h - b * i) * s, (b * f - c * e) * s,
                       (f * g - d * i) * s, (a * i - c * g) * s, (c * d - a * f) * s,
                       (d * h - e * g) * s, (b * g - a * h) * s, (a * e - b * d) * s};
  for (int row = 0; row < 3; ++row) {
    out[row * 4 + 0] = float(r[row * 3 + 0]);
    out[row * 4 + 1] = float(r[row * 3 + 1]);
    out[row * 4 + 2] = float(r[row * 3 + 2]);
    out[row * 4 + 3] = float(-(r[row * 3 + 0] * m[3] + r[row * 3 + 1] * m[7] + r[row * 3 + 2] * m[11]));
  }
  return true;
}

}  // namespace

Transform Transform::from_rows(const Rows& rows, bool& invertible) {
  Transform t;
  t.m_ = rows;
  invertible = invert(rows, t.inv_);
  for (float v : rows) invertible = invertible && std::isfinite(v);
  return t;
}

Transform Transform::translate(Vec3 v) {
  bool ok;
  return from_rows({1, 0, 0, v.x, 0, 1, 0, v.y, 0, 0, 1, v.z}, ok);
}

Transform Transform::scale(Vec3 s) {
  bool ok;
  return from_rows({s.x, 0, 0, 0, 0, s.y, 0, 0, 0, 0, s.z, 0}, ok);
}

Transform Transform::rotate(float angle_deg, Vec3 axis) {
  const Vec3 a = normalize(axis);
  const float theta = angle_deg * float(M_PI / 180.0);
  const float s = std::sin(theta), c = std::cos(theta), k = 1.0f - c;
  // Rodrigues' rotation formula as a matrix.
  bool ok;
  return from_rows({a.x * a.x * k + c, a.x * a.y * k - a.z * s, a.x * a.z * k + a.y * s, 0,
                    a.x * a.y * k + a.z * s, a.y * a.y * k + c, a.y * a.z * k - a.x * s, 0,
                    a.x * a.z * k - a.y * s, a.y * a.z * k + a.x * s, a.z * a.z * k + c, 0},
                   ok);
}

Transform Transform::look_at(Vec3 from, Vec3 to, Vec3 up) {
  // Columns are the camera axes in world space: x (image right), y (image up), z (forward). In a right-handed
  // world, looking along z with y up, image-right is forward × up; y = x × z completes the frame.
  const Vec3 z = normalize(to - from);
  const Vec3 x = normalize(cross(z, up));
  const Vec3 y = cross(x, z);
  bool ok;
  return from_rows({x.x, y.x, z.x, from.x, x.y, y.y, z.y, from.y, x.z, y.z, z.z, from.z}, ok);
}

Vec3 Transform::point(Vec3 p) const {
  return {m_[0] * p.x + m_[1] * p.y + m_[2] * p.z + m_[3], m_[4] * p.x + m_[5] * p.y + m_[6] * p.z + m_[7],
          m_[8] * p.x + m_[9] * p.y + m_[10] * p.z + m_[11]};
}

Vec3 Transform::vector(Vec3 v) const {
  return {m_[0] * v.x + m_[1] * v.y + m_[2] * v.z, m_[4] * v.x + m_[5] * v.y + m_[6] * v.z,
          m_[8] * v.x + m_[9] * v.y + m_[10] * v.z};
}

Vec3 Transform::normal(Vec3 n) const {
  // (M⁻¹)ᵀ n
  return {inv_[0] * n.x + inv_[4] * n.y + inv_[8] * n.z, inv_[1] * n.x + inv_[5] * n.y + inv_[9] * n.z,
          inv_[2] * n.x + inv_[6] * n.y + inv_[10] * n.z};
}

Transform Transform::inverse() const {
  Transform t;
  t.m_ = inv_;
  t.inv_ = m_;
  return t;
}

float Transform::determinant() const {
  return m_[0] * (m_[5] * m_[10] - m_[6] * m_[9]) - m_[1] * (m_[4] * m_[10] - m_[6] * m_[8]) +
         m_[2] * (m_[4] * m_[9] - m_[5] * m_[8]);
}

bool Transform::is_finite() const {
  for (float v : m_)
    if (!std::isfinite(v)) return false;
  return true;
}

Transform operator*(const Transform& a, const Transform& b) {
  Transform t;
  t.m_ = multiply(a.m_, b.m_);
  t.inv_ = multiply(b.inv_, a.inv_);
  return t;
}

}  // namespace rimu
