// A spot light: a point light whose intensity falls off smoothly away from an axis.
//
// Falloff. With cos θ the cosine between the emission direction and the axis, the intensity is I(λ)·s(cos θ),
//   s = 1 inside the inner cone (cos θ ≥ cos θ_inner), 0 outside the outer cone (cos θ ≤ cos θ_outer), and
//   s = t²(3 − 2t), t = (cos θ − cos θ_outer)/(cos θ_inner − cos θ_outer) in between,
// the Hermite smoothstep taken in cos θ (as pbrt-v4 does): it has zero slope at both cone edges, so no visible
// ring. Taking it in cos θ rather than θ makes the power closed-form: ∫₀¹ t²(3 − 2t) dt = 1/2, so
//   Φ = 2π ∫ I s(μ) dμ = 2π I [(1 − cos θ_inner) + (cos θ_inner − cos θ_outer)/2] = 2π I (1 − (cos θ_inner + cos θ_outer)/2).
// `intensity` is the on-axis value. inner = outer gives a hard edge (s is the step; Φ is the same formula).
#pragma once

#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"

namespace rimu {

class SpotLight final : public Light {
 public:
  /// At `position_m`, pointing along `axis` (normalised here), on-axis intensity `intensity` W/(sr·nm), full
  /// intensity inside `inner_half_angle_deg`, none beyond `outer_half_angle_deg`. Asserted:
  /// 0 ≤ inner ≤ outer ≤ 180 and a nonzero axis (the loader reports bad input with its key).
  SpotLight(Vec3 position_m, Vec3 axis, double inner_half_angle_deg, double outer_half_angle_deg,
            LightSpectrum intensity);

  /// As PointLight, with I·s(cos θ); std::nullopt outside the outer cone.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  float pdf_li(const LightReference&, Vec3, const SurfaceHit*) const override { return 0.0f; }
  /// Φ = 2π (1 − (cos θ_inner + cos θ_outer)/2) ∫I(λ) dλ (derivation above).
  double total_power_w(double scene_radius_m) const override;
  bool is_delta() const override { return true; }
  bool samples_emission() const override;
  std::optional<EmissionSample> sample_emission(float u_part, Vec2 u_position, Vec2 u_direction,
                                                const SampledWavelengths& lambda) const override;
  EmissionDensity emission_density(Vec3 normal, Vec3 direction) const override;
  std::optional<Vec3> emission_centre_m(int) const override { return position_m_; }

  /// The on-axis intensity ∫I(λ)dλ in the cone θo = inner, falling to nothing at θo + θe = outer.
  std::optional<LightBounds> part_bounds(int part) const override;

  /// s(cos θ) for the direction `w_emitted` (unit, from the light outwards).
  float falloff(Vec3 w_emitted) const;

  const LightSpectrum* emitted_spectrum() const override { return &intensity_; }

 private:
  Vec3 position_m_;
  Vec3 axis_;
  double cos_inner_, cos_outer_;
  LightSpectrum intensity_;
};

}  // namespace rimu
