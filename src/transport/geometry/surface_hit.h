// What a ray hit.
#pragma once

#include <cstdint>

#include "transport/geometry/vector.h"

namespace rimu {

/// A ray-surface intersection in world space.
struct SurfaceHit {
  float t = 0;                 ///< ray parameter (distance, since ray directions are unit)
  Vec3 position;
  /// The magnitude of the coordinates `position` was computed from (a triangle's vertices, a sphere's centre plus
  /// radius, through an instance's transform): its rounding error is a few units in the last place of this, not of
  /// |position|, so rays leaving the surface are offset in proportion to it (offset_ray_origin).
  float position_scale = 0;
  Vec3 geometric_normal;       ///< unit; the front side of the triangle (counter-clockwise winding) or sphere's outside
  Vec3 shading_normal;         ///< unit; interpolated vertex normal, on the same side as geometric_normal
  Vec2 uv;
  /// ∂p/∂u, ∂p/∂v in world space (not unit): tangents along the texture axes, for normal and bump maps. Zero
  /// where the parametrisation is degenerate (coincident uvs, a sphere's poles).
  Vec3 dpdu, dpdv;
  int32_t material = -1;       ///< index into the scene's materials
  int32_t light = -1;          ///< index into the scene's lights if the surface emits, else -1
  uint32_t primitive = 0;      ///< triangle index within its mesh (for area-light pdfs)
};

}  // namespace rimu
