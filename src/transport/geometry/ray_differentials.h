// Ray differentials: how a ray's footprint spreads, carried as two auxiliary rays (Igehy, "Tracing ray
// differentials", SIGGRAPH 1999; the form pbrt-v4 uses).
#pragma once

#include <optional>

#include "transport/geometry/vector.h"

namespace rimu {

/// The rays through the neighbouring film sample one step to the right (x) and one step down (y), scaled so that
/// the offsets stand for the spacing between this pixel's samples (Renderer: max(1/8, 1/√spp) of a pixel, pbrt-v4's
/// choice). The main ray is not stored here: a path keeps it, and these follow it through specular bounces.
struct RayDifferentials {
  Vec3 rx_origin, rx_direction;  ///< the auxiliary ray for +x; direction unit
  Vec3 ry_origin, ry_direction;  ///< the auxiliary ray for +y; direction unit

  /// Moves the auxiliary rays towards the main ray (origin, direction) by `scale` (1: unchanged): the offsets
  /// are linear in the film step, so scaling them scales the footprint.
  void scale_towards(Vec3 origin, Vec3 direction, float scale) {
    rx_origin = origin + (rx_origin - origin) * scale;
    ry_origin = origin + (ry_origin - origin) * scale;
    rx_direction = normalize(direction + (rx_direction - direction) * scale);
    ry_direction = normalize(direction + (ry_direction - direction) * scale);
  }
};

/// What the auxiliary rays give at a surface point: the world-space offsets of the points they meet on the tangent
/// plane (∂p/∂x, ∂p/∂y per film step) and the texture coordinates' derivatives. All zero = no footprint known (a
/// point-sampled lookup).
struct SurfaceDifferentials {
  Vec3 dpdx, dpdy;
  Vec2 duvdx, duvdy;  ///< (∂u/∂x, ∂v/∂x) and (∂u/∂y, ∂v/∂y)
};

/// The differentials at the hit `p` with unit normal `n` and tangents ∂p/∂u, ∂p/∂v: each auxiliary ray is
/// intersected with the plane through p of normal n, and (∂u/∂x, ∂v/∂x) is the least-squares solution of
/// ∂p/∂x = ∂p/∂u ∂u/∂x + ∂p/∂v ∂v/∂x (three equations, two unknowns: the normal equations, a 2×2 solve). An
/// auxiliary ray parallel to the plane gives no footprint (all zero); degenerate tangents give zero uv
/// derivatives but keep ∂p/∂x, ∂p/∂y. Derivatives are clamped to ±1e8 (pbrt-v4's bound) so a grazing hit stays
/// finite. ~40 flops.
SurfaceDifferentials surface_differentials(Vec3 p, Vec3 n, Vec3 dpdu, Vec3 dpdv, const RayDifferentials& rays);

/// The auxiliary rays after a specular bounce at `p` (the point where the main ray met the surface, differentials
/// `d` there): they leave from p + ∂p/∂x, p + ∂p/∂y and each is mirrored (`transmitted` false) or refracted with
/// relative index `eta` (ηₜ/ηᵢ on the side the main ray was refracted to) about the unit shading normal `n`, as the
/// main ray was. The normal is taken as constant over the footprint (Rimu carries no ∂n/∂u): exact for flat
/// mirrors and panes, an underestimate of the spread after a curved one. nullopt if an auxiliary ray is totally
/// reflected where the main one was not (the footprint is lost; the path goes on point-sampling).
std::optional<RayDifferentials> specular_differentials(const RayDifferentials& incoming, Vec3 p, Vec3 n,
                                                       const SurfaceDifferentials& d, bool transmitted, float eta);

}  // namespace rimu
