// Light carried from the light's side (light tracing, bidirectional light subpaths) over surfaces with shading
// normals: the factor by which the BSDF differs from its adjoint.
#pragma once

#include <cmath>

#include "transport/geometry/vector.h"

namespace rimu {

/// |ωo·n_s||ωi·n_g| / (|ωo·n_g||ωi·n_s|): the factor by which a BSDF with shading normals differs from its adjoint
/// (Veach 1997, §5.3), ωo towards the light, ωi the other way; 0 where a cosine with the geometric normal vanishes
/// (the path grazes the surface).
inline float adjoint_shading_factor(Vec3 wo, Vec3 wi, Vec3 ns, Vec3 ng) {
  const float denominator = std::fabs(dot(wo, ng)) * std::fabs(dot(wi, ns));
  if (!(denominator > 0.0f)) return 0.0f;
  const float factor = std::fabs(dot(wo, ns)) * std::fabs(dot(wi, ng)) / denominator;
  return std::isfinite(factor) ? factor : 0.0f;
}

}  // namespace rimu
