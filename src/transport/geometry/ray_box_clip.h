// The piece of a ray inside an axis-aligned box, and the box's own space, for media that live in a box of their own
// space (grids, the noise cloud).
#pragma once

#include <algorithm>
#include <cmath>

#include "spectral/error.h"
#include "transport/geometry/ray.h"
#include "transport/geometry/transform.h"

namespace rimu {

/// [t0, t1] = the part of [ray.t_min, t_max] inside the box [lo, hi], by the slab test (Kay & Kajiya 1986: intersect
/// the three pairs of planes). The direction need not be unit length. An axis the ray runs parallel to with its
/// origin on one of that axis's planes (0·∞ = NaN) does not clip. False if the piece is empty.
inline bool clip_ray_to_box(const Ray& ray, float t_max, Vec3 lo, Vec3 hi, float& t0, float& t1) {
  t0 = ray.t_min;
  t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / ray.direction[a];
    float near = (lo[a] - ray.origin[a]) * inv, far = (hi[a] - ray.origin[a]) * inv;
    if (near > far) std::swap(near, far);
    if (std::isnan(near)) continue;
    t0 = std::fmax(t0, near);
    t1 = std::fmin(t1, far);
  }
  return t0 < t1;
}

/// The inverse of a box's placement in the world (the box's own space from the world's). Throws InputError if the
/// placement is not finite and invertible.
inline Transform box_from_world(const Transform& world_from_box) {
  if (!world_from_box.is_finite() || !(std::fabs(world_from_box.determinant()) > 1e-30f))
    throw InputError({}, "the medium's transform must be finite and invertible");
  return world_from_box.inverse();
}

}  // namespace rimu
