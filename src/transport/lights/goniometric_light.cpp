#include "transport/lights/goniometric_light.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "transport/lights/point_light.h"

namespace rimu {

GoniometricLight::GoniometricLight(Vec3 position_m, Vec3 axis, Vec3 c0_direction, LightSpectrum per_unit_intensity,
                                   std::shared_ptr<const IntensityDistribution> table)
    : position_m_(position_m), per_unit_intensity_(std::move(per_unit_intensity)), table_(std::move(table)) {
  const Vec3 n = normalize(axis);
  const Vec3 s = normalize(c0_direction - n * dot(c0_direction, n));
  assert(is_finite(s));
  // C increases counter-clockwise seen from the side opposite the axis (looking down onto a downlight from above),
  // so C = 90° is the t with s × t = −n: t = s × n (then s × (s × n) = s (s·n) − n (s·s) = −n).
  frame_ = Frame{s, cross(s, n), n};
}

GoniometricLight::GoniometricLight(Vec3 position_m, Frame frame, LightSpectrum per_unit_intensity,
                                   std::shared_ptr<const IntensityDistribution> table)
    : position_m_(position_m), frame_(frame), per_unit_intensity_(std::move(per_unit_intensity)), table_(std::move(table)) {}

std::optional<LightSample> GoniometricLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                       Vec2 u) const {
  Vec3 origin = position_m_;
  LuminousOpening::SurfacePoint on_opening{};
  if (!opening_.is_point()) {
    on_opening = opening_.sample(u);
    origin = position_m_ + frame_.to_world(on_opening.position_m);
  }
  const Vec3 to_ref = ref.position - origin;
  const float d = length(to_ref);
  if (!(d > 0.0f) || !std::isfinite(d)) return std::nullopt;
  const Vec3 w_out = to_ref / d;
  double candela = table_value(w_out);
  if (!opening_.is_point()) candela *= opening_.weight(on_opening.normal, frame_.to_local(w_out));
  if (!(candela > 0.0)) return std::nullopt;
  return delta_position_sample(origin, ref, per_unit_intensity_.sample(lambda) * Float4(float(candela)));
}

double GoniometricLight::total_power_w(double) const {
  return per_unit_intensity_.integral_360_830() * table_->integral_sr();
}

std::optional<LightBounds> GoniometricLight::part_bounds(int part) const {
  const double intensity = per_unit_intensity_.integral_360_830() * table_->peak();
  if (part != 0 || !(intensity > 0.0)) return std::nullopt;
  const auto gamma = table_->nonzero_gamma_rad();
  if (!gamma) return std::nullopt;
  const auto [gamma_min, gamma_max] = *gamma;
  const double i = intensity;
  LightBounds bounds = gamma_max <= std::numbers::pi - gamma_min
                           ? point_light_bounds(position_m_, i, frame_.n, gamma_max, 0.0)
                           : point_light_bounds(position_m_, i, -frame_.n, std::numbers::pi - gamma_min, 0.0);
  if (!opening_.is_point()) {
    // The opening's local box in world space: half extents |s|·hx + |t|·hy + |n|·hz per axis.
    const Vec3 h = opening_.half_extent_m();
    const auto abs3 = [](Vec3 v) { return Vec3{std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; };
    const Vec3 e = abs3(frame_.s) * h.x + abs3(frame_.t) * h.y + abs3(frame_.n) * h.z;
    bounds.lower_m = bounds.lower_m - e;
    bounds.upper_m = bounds.upper_m + e;
  }
  return bounds;
}

std::optional<IntensityDistribution::DirectionSample> GoniometricLight::sample_emission_direction(Vec2 u) const {
  auto s = table_->sample(u);
  if (s) s->w = frame_.to_world(s->w);
  return s;
}

}  // namespace rimu

namespace rimu {

bool GoniometricLight::samples_emission() const {
  return opening_.is_point() && per_unit_intensity_.integral_360_830() > 0.0 && table_->integral_sr() > 0.0;
}

std::optional<EmissionSample> GoniometricLight::sample_emission(float, Vec2, Vec2 u_direction,
                                                                const SampledWavelengths& lambda) const {
  if (!samples_emission()) return std::nullopt;
  // A direction in proportion to the table (its own sampler), weighted by table/p_ω.
  const auto s = sample_emission_direction(u_direction);
  if (!s || !(s->pdf > 0.0f)) return std::nullopt;
  const double candela = table_value(s->w);
  if (!(candela > 0.0)) return std::nullopt;
  return EmissionSample{position_m_, s->w, Vec3{}, per_unit_intensity_.sample(lambda) * Float4(float(candela / s->pdf)),
                        1.0f, s->pdf};
}

EmissionDensity GoniometricLight::emission_density(Vec3, Vec3 direction) const {
  if (!samples_emission()) return {};
  return {1.0f, table_->pdf(frame_.to_local(direction))};
}

}  // namespace rimu
