#include "transport/lights/point_light.h"
#include "transport/lights/light_warps.h"

#include <cmath>
#include <numbers>

namespace rimu {

std::optional<LightSample> delta_position_sample(Vec3 light_position_m, const LightReference& ref,
                                                 SampledSpectrum intensity) {
  const Vec3 to_light = light_position_m - ref.position;
  const float distance_squared = length_squared(to_light);
  // At the light itself the direction is undefined and I/d² infinite; underflow (d < 1e-19 m) likewise.
  if (!(distance_squared > 0.0f) || !std::isfinite(distance_squared)) return std::nullopt;
  const float distance = std::sqrt(distance_squared);
  LightSample s;
  s.wi = to_light / distance;
  s.distance = distance;
  s.radiance = intensity / Float4(distance_squared);
  s.pdf_solid_angle = 1.0f;
  s.is_delta = true;
  return s;
}

std::optional<LightSample> PointLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                 Vec2) const {
  if (intensity_.is_black()) return std::nullopt;
  return delta_position_sample(position_m_, ref, intensity_.sample(lambda));
}

std::optional<LightBounds> PointLight::part_bounds(int part) const {
  if (part != 0 || intensity_.is_black()) return std::nullopt;
  return point_light_bounds(position_m_, intensity_.integral_360_830(), {0, 0, 1}, std::numbers::pi, 0.0);
}

double PointLight::total_power_w(double) const { return 4.0 * std::numbers::pi * intensity_.integral_360_830(); }

}  // namespace rimu

namespace rimu {

bool PointLight::samples_emission() const { return !intensity_.is_black(); }

std::optional<EmissionSample> PointLight::sample_emission(float, Vec2, Vec2 u_direction,
                                                          const SampledWavelengths& lambda) const {
  if (intensity_.is_black()) return std::nullopt;
  // A uniform direction (p_ω = 1/4π): the weight I/p_ω is the same for every direction.
  return EmissionSample{position_m_, sample_uniform_sphere(u_direction), Vec3{},
                        intensity_.sample(lambda) * Float4(4.0f * std::numbers::pi_v<float>), 1.0f,
                        0.25f * std::numbers::inv_pi_v<float>};
}

EmissionDensity PointLight::emission_density(Vec3, Vec3) const {
  if (intensity_.is_black()) return {};
  return {1.0f, 0.25f * std::numbers::inv_pi_v<float>};
}

}  // namespace rimu
