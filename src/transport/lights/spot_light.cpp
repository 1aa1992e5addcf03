#include "transport/lights/spot_light.h"
#include "transport/lights/light_warps.h"
#include "transport/geometry/frame.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "transport/lights/point_light.h"

namespace rimu {

SpotLight::SpotLight(Vec3 position_m, Vec3 axis, double inner_half_angle_deg, double outer_half_angle_deg,
                     LightSpectrum intensity)
    : position_m_(position_m), axis_(normalize(axis)), intensity_(std::move(intensity)) {
  assert(length_squared(axis) > 0.0f && is_finite(axis_));
  assert(0.0 <= inner_half_angle_deg && inner_half_angle_deg <= outer_half_angle_deg && outer_half_angle_deg <= 180.0);
  const double to_rad = std::numbers::pi / 180.0;
  cos_inner_ = std::cos(inner_half_angle_deg * to_rad);
  cos_outer_ = std::cos(outer_half_angle_deg * to_rad);
}

float SpotLight::falloff(Vec3 w_emitted) const {
  const double cos_theta = dot(w_emitted, axis_);
  if (cos_theta >= cos_inner_) return 1.0f;
  if (cos_theta <= cos_outer_) return 0.0f;
  // Here cos_outer < cos θ < cos_inner, so the width is positive (a hard edge never reaches this line).
  const double t = (cos_theta - cos_outer_) / (cos_inner_ - cos_outer_);
  return float(t * t * (3.0 - 2.0 * t));
}

std::optional<LightSample> SpotLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                Vec2) const {
  if (intensity_.is_black()) return std::nullopt;
  auto s = delta_position_sample(position_m_, ref, Float4(1.0f));
  if (!s) return std::nullopt;
  const float f = falloff(-s->wi);
  if (f <= 0.0f) return std::nullopt;
  s->radiance = s->radiance * intensity_.sample(lambda) * Float4(f);
  return s;
}

std::optional<LightBounds> SpotLight::part_bounds(int part) const {
  if (part != 0 || intensity_.is_black()) return std::nullopt;
  const double inner = std::acos(std::clamp(cos_inner_, -1.0, 1.0));
  const double outer = std::acos(std::clamp(cos_outer_, -1.0, 1.0));
  return point_light_bounds(position_m_, intensity_.integral_360_830(), axis_, inner, outer - inner);
}

double SpotLight::total_power_w(double) const {
  return 2.0 * std::numbers::pi * (1.0 - 0.5 * (cos_inner_ + cos_outer_)) * intensity_.integral_360_830();
}

}  // namespace rimu

namespace rimu {

bool SpotLight::samples_emission() const { return !intensity_.is_black(); }

std::optional<EmissionSample> SpotLight::sample_emission(float, Vec2, Vec2 u_direction,
                                                         const SampledWavelengths& lambda) const {
  if (intensity_.is_black()) return std::nullopt;
  // Uniform in the outer cone (p_ω = 1/(2π(1 − cos θ_outer))), weighted by the falloff: nothing is sent outside it.
  const float one_minus_cos_outer = float(1.0 - cos_outer_);
  if (!(one_minus_cos_outer > 0.0f)) return std::nullopt;
  const Vec3 direction = Frame::from_normal(axis_).to_world(sample_uniform_cone(u_direction, one_minus_cos_outer));
  const float s = falloff(direction);
  if (!(s > 0.0f)) return std::nullopt;
  const float inverse_pdf = 2.0f * std::numbers::pi_v<float> * one_minus_cos_outer;
  return EmissionSample{position_m_, direction, Vec3{}, intensity_.sample(lambda) * Float4(s * inverse_pdf), 1.0f,
                        1.0f / inverse_pdf};
}

EmissionDensity SpotLight::emission_density(Vec3, Vec3 direction) const {
  const float one_minus_cos_outer = float(1.0 - cos_outer_);
  if (intensity_.is_black() || !(one_minus_cos_outer > 0.0f) || !(dot(direction, axis_) >= float(cos_outer_)))
    return {};
  return {1.0f, 1.0f / (2.0f * std::numbers::pi_v<float> * one_minus_cos_outer)};
}

}  // namespace rimu
