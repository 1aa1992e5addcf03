// An orthonormal shading frame: local coordinates in which the normal is +z.
#pragma once

#include <cmath>

#include "transport/geometry/vector.h"

namespace rimu {

/// Orthonormal basis (s, t, n). BSDFs work in local coordinates, where cos θ = v.z.
struct Frame {
  Vec3 s, t, n;

  /// A frame around unit normal `n`, without branches that break continuity except at n.z = -0
  /// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017).
  static Frame from_normal(Vec3 n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3 to_world(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

/// Trigonometry of a direction in local (shading) coordinates.
inline float cos_theta(Vec3 w) { return w.z; }
inline float abs_cos_theta(Vec3 w) { return std::fabs(w.z); }
inline float cos2_theta(Vec3 w) { return w.z * w.z; }
inline float sin2_theta(Vec3 w) { return std::fmax(0.0f, 1.0f - w.z * w.z); }
inline float tan2_theta(Vec3 w) { return sin2_theta(w) / cos2_theta(w); }
inline bool same_hemisphere(Vec3 a, Vec3 b) { return a.z * b.z > 0.0f; }
/// -1 when w is below the shading plane, else +1: two-sided BSDFs mirror both directions by it (flip_z) and
/// evaluate the upper side.
inline float side_of(Vec3 w) { return w.z < 0.0f ? -1.0f : 1.0f; }
/// w mirrored through the shading plane when side is -1 (unchanged for +1).
inline Vec3 flip_z(Vec3 w, float side) { return {w.x, w.y, w.z * side}; }

}  // namespace rimu
