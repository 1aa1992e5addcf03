#include "transport/geometry/motion_transform.h"

#include <algorithm>
#include <cmath>

namespace rimu {
namespace {

using Matrix3 = std::array<double, 9>;
using Quaternion = std::array<double, 4>;  // x, y, z, w

double determinant(const Matrix3& a) {
  return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) + a[2] * (a[3] * a[7] - a[4] * a[6]);
}

// (A⁻¹)ᵀ: the cofactor matrix over the determinant.
Matrix3 inverse_transpose(const Matrix3& a) {
  const double s = 1.0 / determinant(a);
  return {(a[4] * a[8] - a[5] * a[7]) * s, (a[5] * a[6] - a[3] * a[8]) * s, (a[3] * a[7] - a[4] * a[6]) * s,
          (a[2] * a[7] - a[1] * a[8]) * s, (a[0] * a[8] - a[2] * a[6]) * s, (a[1] * a[6] - a[0] * a[7]) * s,
          (a[1] * a[5] - a[2] * a[4]) * s, (a[2] * a[3] - a[0] * a[5]) * s, (a[0] * a[4] - a[1] * a[3]) * s};
}

// Shoemake's conversion of a proper rotation matrix, branching on the largest of w², x², y², z² for accuracy.
Quaternion quaternion_of(const Matrix3& r) {
  const double trace = r[0] + r[4] + r[8];
  Quaternion q;
  if (trace > 0) {
    const double s = 2.0 * std::sqrt(trace + 1.0);
    q = {(r[7] - r[5]) / s, (r[2] - r[6]) / s, (r[3] - r[1]) / s, 0.25 * s};
  } else if (r[0] > r[4] && r[0] > r[8]) {
    const double s = 2.0 * std::sqrt(1.0 + r[0] - r[4] - r[8]);
    q = {0.25 * s, (r[1] + r[3]) / s, (r[2] + r[6]) / s, (r[7] - r[5]) / s};
  } else if (r[4] > r[8]) {
    const double s = 2.0 * std::sqrt(1.0 + r[4] - r[0] - r[8]);
    q = {(r[1] + r[3]) / s, 0.25 * s, (r[5] + r[7]) / s, (r[2] - r[6]) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + r[8] - r[0] - r[4]);
    q = {(r[2] + r[6]) / s, (r[5] + r[7]) / s, 0.25 * s, (r[3] - r[1]) / s};
  }
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= n;
  return q;
}

Matrix3 rotation_matrix(const Quaternion& q) {
  const auto [x, y, z, w] = q;
  return {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
          2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
          2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
}

double dot(const Quaternion& a, const Quaternion& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]; }

Quaternion slerp(const Quaternion& a, const Quaternion& b, double t) {
  const double cos_theta = std::clamp(dot(a, b), -1.0, 1.0);
  Quaternion q;
  if (cos_theta > 0.9995) {
    // Nearly the same rotation: sin θ would lose its digits; the normalised chord is the arc to double precision.
    for (int k = 0; k < 4; ++k) q[k] = (1 - t) * a[k] + t * b[k];
  } else {
    const double theta = std::acos(cos_theta), s = std::sin(theta);
    const double wa = std::sin((1 - t) * theta) / s, wb = std::sin(t * theta) / s;
    for (int k = 0; k < 4; ++k) q[k] = wa * a[k] + wb * b[k];
  }
  const double n = std::sqrt(dot(q, q));
  for (double& c : q) c /= n;
  return q;
}

Transform compose(const Vec3& translation, const Quaternion& rotation, const Matrix3& stretch) {
  const Matrix3 r = rotation_matrix(rotation);
  std::array<float, 12> rows{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      rows[4 * i + j] = float(r[3 * i] * stretch[j] + r[3 * i + 1] * stretch[3 + j] + r[3 * i + 2] * stretch[6 + j]);
  }
  rows[3] = translation.x;
  rows[7] = translation.y;
  rows[11] = translation.z;
  bool invertible = false;
  return Transform::from_rows(rows, invertible);
}

}  // namespace

TransformComponents decompose(const Transform& m) {
  const std::array<float, 12>& rows = m.rows();
  TransformComponents c;
  c.translation = {rows[3], rows[7], rows[11]};
  Matrix3 a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[3 * i + j] = rows[4 * i + j];
  // A mirror (det < 0) is a proper rotation times a negative stretch: decompose −A, then negate its stretch.
  const double sign = determinant(a) < 0 ? -1.0 : 1.0;
  for (double& v : a) v *= sign;
  // Higham's iteration converges quadratically to the orthogonal polar factor of a non-singular matrix.
  Matrix3 r = a;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Matrix3 it = inverse_transpose(r);
    double change = 0;
    for (int k = 0; k < 9; ++k) {
      const double next = 0.5 * (r[k] + it[k]);
      change = std::max(change, std::fabs(next - r[k]));
      r[k] = next;
    }
    if (change < 1e-14) break;
  }
  c.rotation = quaternion_of(r);
  // S = Rᵀ·A (symmetric; made exactly so, since the iteration stops at rounding), times the mirror's sign.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      c.stretch[3 * i + j] = sign * (r[i] * a[j] + r[3 + i] * a[3 + j] + r[6 + i] * a[6 + j]);
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      c.stretch[3 * i + j] = c.stretch[3 * j + i] = 0.5 * (c.stretch[3 * i + j] + c.stretch[3 * j + i]);
  return c;
}

MotionTransform::MotionTransform(const Transform& start, const Transform& end, bool& valid)
    : start_(start), end_(end), from_(decompose(start)), to_(decompose(end)) {
  valid = (start.determinant() < 0) == (end.determinant() < 0);
  // q and −q are the same rotation: take the one nearer the start, so the slerp turns the shorter way.
  if (dot(from_.rotation, to_.rotation) < 0)
    for (double& c : to_.rotation) c = -c;
  rotation_angle_ = 2.0 * std::acos(std::clamp(dot(from_.rotation, to_.rotation), -1.0, 1.0));
}

Transform MotionTransform::at(float time) const {
  if (!(time > 0.0f)) return start_;
  if (time >= 1.0f) return end_;
  const double t = time;
  const Vec3 translation = from_.translation * float(1 - t) + to_.translation * float(t);
  Matrix3 stretch;
  for (int k = 0; k < 9; ++k) stretch[k] = (1 - t) * from_.stretch[k] + t * to_.stretch[k];
  return compose(translation, slerp(from_.rotation, to_.rotation, t), stretch);
}

std::vector<Transform> MotionTransform::linear_keys(double max_segment_angle) const {
  // Embree takes at most 129 time steps; 128 segments of a half turn are 1.4° each.
  int segments = 1;
  if (rotation_angle_ > 0) segments = int(std::clamp(std::ceil(rotation_angle_ / max_segment_angle), 1.0, 128.0));
  std::vector<Transform> keys(size_t(segments) + 1);
  keys.front() = start_;
  keys.back() = end_;
  for (int i = 1; i < segments; ++i) keys[size_t(i)] = at(float(i) / float(segments));
  return keys;
}

Transform interpolate_keys(const std::vector<Transform>& keys, float time) {
  if (keys.size() == 1) return keys.front();
  const float segments = float(keys.size() - 1);
  const float scaled = std::clamp(time, 0.0f, 1.0f) * segments;
  const float index = std::clamp(std::floor(scaled), 0.0f, segments - 1.0f);
  const float f = scaled - index;
  const std::array<float, 12>& a = keys[size_t(index)].rows();
  const std::array<float, 12>& b = keys[size_t(index) + 1].rows();
  std::array<float, 12> rows;
  for (int k = 0; k < 12; ++k) rows[k] = (1.0f - f) * a[k] + f * b[k];
  bool invertible = false;
  return Transform::from_rows(rows, invertible);
}

}  // namespace rimu
