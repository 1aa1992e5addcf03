// 4x4 matrices for pbrt-v4's graphics state, in double precision (the CTM is a product of many statements).
// pbrt transforms points as column vectors, p_world = CTM · p_object; each transform statement post-multiplies.
#pragma once

#include <array>
#include <optional>

namespace rimu {

struct PbrtMatrix {
  std::array<std::array<double, 4>, 4> m{};  ///< m[row][column]

  static PbrtMatrix identity();
  static PbrtMatrix translate(double x, double y, double z);
  static PbrtMatrix scale(double x, double y, double z);
  /// Rotation by `angle_deg` about the axis (x, y, z), right-handed (pbrt's Rotate). The axis must not be zero.
  static PbrtMatrix rotate(double angle_deg, double x, double y, double z);
  /// pbrt's LookAt: camera-from-world for an eye at `eye` looking at `look` with `up` (camera +x = up × dir,
  /// +y = dir × x, +z = dir). Empty when up is parallel to the view direction or eye = look.
  static std::optional<PbrtMatrix> look_at(const std::array<double, 3>& eye, const std::array<double, 3>& look,
                                           const std::array<double, 3>& up);
  /// The 16 numbers of pbrt's Transform/ConcatTransform, which list the matrix column by column.
  static PbrtMatrix from_pbrt_numbers(const double* sixteen);

  PbrtMatrix operator*(const PbrtMatrix& o) const;
  std::array<double, 3> point(const std::array<double, 3>& p) const;   ///< affine part only (w ignored)
  std::array<double, 3> vector(const std::array<double, 3>& v) const;  ///< linear part
  double determinant3() const;  ///< of the linear part
  /// Empty when singular or not finite.
  std::optional<PbrtMatrix> inverse() const;
  bool is_affine() const;  ///< last row (0 0 0 1)
  bool is_identity() const;
  bool is_finite() const;
};

}  // namespace rimu
