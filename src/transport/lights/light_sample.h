// The result of sampling a light from a shading point, and the contract every light follows.
//
// Conventions (all lights):
// - World space. wi points FROM the shading point TOWARDS the light (unit length).
// - sample_li(ref, lambda, u) picks a point/direction on the light with a density that does not depend on the
//   wavelength (lights are sampled by geometry and, for images, by luminance), and returns the radiance arriving
//   along -wi per lane, the density in SOLID ANGLE at the shading point (for a delta light: 1 and is_delta), and the
//   distance to the light point (infinite for distant/environment lights) for the shadow ray.
// - pdf_li(ref, wi, ...) is the same solid-angle density for a direction that BSDF sampling produced and that hit
//   the light (area lights) or escaped to it (environment), so the integrator can weight the two strategies.
// - Radiometric units: radiance in W/(m²·sr·nm), intensity in W/(sr·nm), irradiance in W/(m²·nm). The photometric
//   layer (issue 5) converts lm/cd/lx/nt to these at scene load, never per sample.
#pragma once

#include <limits>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/geometry/vector.h"

namespace rimu {

struct LightSample {
  SampledSpectrum radiance;  ///< L arriving at the reference point along -wi, per lane (intensity/d² for point lights)
  Vec3 wi;                   ///< unit direction from the reference point to the light
  float distance = std::numeric_limits<float>::infinity();  ///< to the sampled point; infinity for lights at infinity
  float pdf_solid_angle = 0;  ///< density of wi; 1 for delta lights
  bool is_delta = false;      ///< point, spot and distant lights with zero angular size: no MIS with BSDF sampling
  /// The light's geometric normal at the sampled point, for lights with a surface there (area lights); zero
  /// otherwise. Shadow rays stop short of that surface along it (shadow_segment in path_integrator.h).
  Vec3 normal{};
  /// Set by Light::sample_part_li_deferred when `radiance` is not evaluated yet: Light::resolve_radiance fills it in.
  bool radiance_pending = false;
};

/// Where a light is being sampled from.
struct LightReference {
  Vec3 position;
  Vec3 normal;  ///< geometric normal (zero for a point in a medium); lights may use it to sample better
};

}  // namespace rimu
