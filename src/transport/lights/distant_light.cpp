#include "transport/lights/distant_light.h"

#include <cassert>
#include <cmath>
#include <numbers>

#include "transport/geometry/frame.h"
#include "transport/lights/light_warps.h"

namespace rimu {

DistantLight::DistantLight(Vec3 direction_to_light, LightSpectrum irradiance, double angular_diameter_deg)
    : axis_(normalize(direction_to_light)), irradiance_(std::move(irradiance)) {
  assert(is_finite(axis_) && angular_diameter_deg >= 0.0 && angular_diameter_deg < 180.0);
  if (angular_diameter_deg > 0.0) {
    const double alpha = 0.5 * angular_diameter_deg * std::numbers::pi / 180.0;
    const double s = std::sin(0.5 * alpha);
    one_minus_cos_alpha_ = 2.0 * s * s;
    const double sin_alpha = std::sin(alpha);
    radiance_per_irradiance_ = 1.0 / (std::numbers::pi * sin_alpha * sin_alpha);
  }
}

double DistantLight::cone_solid_angle_sr() const { return 2.0 * std::numbers::pi * one_minus_cos_alpha_; }

bool DistantLight::inside_cone(Vec3 direction) const {
  return one_minus_cos_between(direction, axis_) <= float(one_minus_cos_alpha_);
}

std::optional<LightSample> DistantLight::sample_li(const LightReference&, const SampledWavelengths& lambda,
                                                   Vec2 u) const {
  if (irradiance_.is_black()) return std::nullopt;
  LightSample s;
  if (is_delta()) {
    s.wi = axis_;
    s.radiance = irradiance_.sample(lambda);
    s.pdf_solid_angle = 1.0f;
    s.is_delta = true;
    return s;
  }
  const Frame frame = Frame::from_normal(axis_);
  s.wi = normalize(frame.to_world(sample_uniform_cone(u, float(one_minus_cos_alpha_))));
  s.radiance = irradiance_.sample(lambda) * Float4(float(radiance_per_irradiance_));
  s.pdf_solid_angle = float(1.0 / cone_solid_angle_sr());
  return s;
}

float DistantLight::pdf_li(const LightReference&, Vec3 wi, const SurfaceHit*) const {
  if (is_delta() || irradiance_.is_black() || !inside_cone(wi)) return 0.0f;
  return float(1.0 / cone_solid_angle_sr());
}

SampledSpectrum DistantLight::radiance_escaped(Vec3 direction, const SampledWavelengths& lambda) const {
  if (is_delta() || !inside_cone(direction)) return Float4(0.0f);
  return irradiance_.sample(lambda) * Float4(float(radiance_per_irradiance_));
}

double DistantLight::total_power_w(double scene_radius_m) const {
  return std::numbers::pi * scene_radius_m * scene_radius_m * irradiance_.integral_360_830();
}

}  // namespace rimu
