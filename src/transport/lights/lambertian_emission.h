// A ray of emission from a point drawn uniformly over a Lambertian emitter (an emitting triangle mesh, a sphere):
// what AreaLight::sample_emission and SphereLight::sample_emission share.
#pragma once

#include <cmath>
#include <numbers>

#include "transport/geometry/frame.h"
#include "transport/lights/light.h"
#include "transport/sampling/direction_warps.h"

namespace rimu {

/// lambertian_emission's densities: p_A = 1/A (1/(2A) with the side's choice of a two-sided emitter), p_ω = |cos|/π
/// about the emitting side's `normal`.
inline EmissionDensity lambertian_emission_density(Vec3 normal, Vec3 direction, bool two_sided, double area_m2) {
  const float sides = two_sided ? 2.0f : 1.0f;
  return {float(1.0 / (double(sides) * area_m2)), std::fabs(dot(normal, direction)) * std::numbers::inv_pi_v<float>};
}

/// From `origin_m`, drawn with density 1/A over an emitter of area `area_m2` whose front normal there is
/// `front_normal`: the back side where a two-sided emitter chose it (`back`, each side with probability ½), a
/// cosine-weighted direction about that side's normal (p_ω = cos/π), and the weight L·cos/(p_A p_ω) = π A L, twice
/// that for a two-sided emitter.
inline EmissionSample lambertian_emission(Vec3 origin_m, Vec3 front_normal, bool two_sided, bool back,
                                          Vec2 u_direction, const SampledSpectrum& radiance, double area_m2) {
  const Vec3 normal = two_sided && back ? -front_normal : front_normal;
  const Vec3 direction = Frame::from_normal(normal).to_world(sample_cosine_hemisphere(u_direction));
  const float sides = two_sided ? 2.0f : 1.0f;
  EmissionSample sample{origin_m, direction, normal,
                        radiance * Float4(sides * std::numbers::pi_v<float> * float(area_m2))};
  const EmissionDensity density = lambertian_emission_density(normal, direction, two_sided, area_m2);
  sample.pdf_position = density.position;
  sample.pdf_direction = density.direction;
  return sample;
}

}  // namespace rimu
