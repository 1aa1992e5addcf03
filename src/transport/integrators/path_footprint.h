// Texture footprints along a path, shared by the surface and volumetric integrators: the camera ray's differentials
// (transport/geometry/ray_differentials.h) give each textured hit its footprint (MaterialContext's ∂p/∂x … ∂uv/∂y,
// which MIP filtering and bump mapping read) and follow the path through specular bounces and straight passages
// (panes, medium boundaries, free flights without scattering). Any other bounce — diffuse, glossy, or a scattering
// in a medium — ends them: the spread of such a bounce is not what two auxiliary rays describe, and later hits are
// point-sampled (MIP level 0), as before differentials existed.
#pragma once

#include <cmath>
#include <optional>

#include "transport/geometry/ray_differentials.h"
#include "transport/geometry/surface_hit.h"
#include "transport/textures/material_context.h"

namespace rimu {

/// Sets `context`'s footprint at `hit` from the differentials arriving there, and returns it.
inline SurfaceDifferentials set_footprint(MaterialContext& context, const SurfaceHit& hit,
                                          const RayDifferentials& arriving) {
  const SurfaceDifferentials d = surface_differentials(hit.position, hit.geometric_normal, hit.dpdu, hit.dpdv, arriving);
  context.dpdx = d.dpdx;
  context.dpdy = d.dpdy;
  context.duvdx = d.duvdx;
  context.duvdy = d.duvdy;
  return d;
}

/// The differentials leaving a surface vertex at `position` (footprint `at_hit` there, from set_footprint) after a
/// BSDF sample from `wo` to `wi` (both local to the shading frame, whose normal is `shading_normal` in world space): mirrored or refracted as the main ray was when the sample
/// is a delta lobe, ended otherwise. The relative index comes from Snell's law on the main ray's own sines (a
/// BsdfSample carries no η); within 1e-4 of normal incidence the sines cannot give it and 1 is taken: the footprint
/// then goes on as if the interface were not there (right for a thin pane; up to η times too narrow or wide behind a
/// thick refracting surface seen head-on).
inline std::optional<RayDifferentials> footprint_after_bounce(const RayDifferentials& arriving,
                                                              const SurfaceDifferentials& at_hit, Vec3 position,
                                                              Vec3 shading_normal, Vec3 wo, Vec3 wi, bool is_delta) {
  if (!is_delta || at_hit.dpdx == Vec3{}) return std::nullopt;
  const bool transmitted = wi.z * wo.z < 0.0f;
  const float sin_i = std::sqrt(std::fmax(0.0f, 1.0f - wo.z * wo.z));
  const float sin_t = std::sqrt(std::fmax(0.0f, 1.0f - wi.z * wi.z));
  const float eta = transmitted && sin_t > 1e-4f ? sin_i / sin_t : 1.0f;
  return specular_differentials(arriving, position, shading_normal, at_hit, transmitted, eta);
}

}  // namespace rimu
