// Affine transforms of points, directions and normals.
#pragma once

#include <array>

#include "transport/geometry/vector.h"

namespace rimu {

/// An affine map x → M·x + t, stored as a row-major 3x4 matrix with its inverse (for normals).
class Transform {
 public:
  Transform() = default;
  static Transform translate(Vec3 t);
  static Transform scale(Vec3 s);
  /// Rotation by `angle_deg` about `axis` (right-handed).
  static Transform rotate(float angle_deg, Vec3 axis);
  /// Camera-to-world for a camera at `from` looking at `to`: camera +z points at `to`, +y towards
  /// `up`, +x = z × y is image-right (right-handed world).
  static Transform look_at(Vec3 from, Vec3 to, Vec3 up);
  /// From 12 row-major numbers (3 rows of 4). Returns false in `invertible` if the linear part is singular.
  static Transform from_rows(const std::array<float, 12>& rows, bool& invertible);

  Vec3 point(Vec3 p) const;
  Vec3 vector(Vec3 v) const;
  /// Normals transform by the inverse transpose.
  Vec3 normal(Vec3 n) const;
  Transform inverse() const;
  /// Determinant of the linear part (negative: handedness flips, so triangle winding flips).
  float determinant() const;
  bool is_finite() const;
  const std::array<float, 12>& rows() const { return m_; }

  friend Transform operator*(const Transform& a, const Transform& b);

 private:
  std::array<float, 12> m_{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  std::array<float, 12> inv_{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
};

}  // namespace rimu
