#include "transport/lights/point_light.h"

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
