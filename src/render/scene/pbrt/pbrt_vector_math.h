// The few vector operations the pbrt importer does in double precision, on Vec3d (std::array<double, 3>).
#pragma once

#include <array>
#include <cmath>

namespace rimu::pbrt_math {

using Vec3d = std::array<double, 3>;

inline Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }
inline Vec3d normalized(const Vec3d& a) {
  const double l = length(a);
  return {a[0] / l, a[1] / l, a[2] / l};
}

}  // namespace rimu::pbrt_math
