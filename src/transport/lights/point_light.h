// An isotropic point light: spectral intensity I(λ) in W/(sr·nm) from one position.
#pragma once

#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"

namespace rimu {

class PointLight final : public Light {
 public:
  /// A point at `position_m` (world space) emitting `intensity` W/(sr·nm) equally in all directions.
  PointLight(Vec3 position_m, LightSpectrum intensity) : position_m_(position_m), intensity_(std::move(intensity)) {}

  /// The direction to the light; radiance field I/d² (the delta's coefficient), pdf 1, is_delta. std::nullopt when
  /// the reference is at the light (d = 0) or the light is black.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  /// 0: BSDF sampling never hits a point.
  float pdf_li(const LightReference&, Vec3, const SurfaceHit*) const override { return 0.0f; }
  /// Φ = 4π ∫I(λ) dλ.
  double total_power_w(double scene_radius_m) const override;
  bool is_delta() const override { return true; }
  bool samples_emission() const override;
  std::optional<EmissionSample> sample_emission(float u_part, Vec2 u_position, Vec2 u_direction,
                                                const SampledWavelengths& lambda) const override;
  EmissionDensity emission_density(Vec3 normal, Vec3 direction) const override;
  std::optional<Vec3> emission_centre_m(int) const override { return position_m_; }

  Vec3 position_m() const { return position_m_; }
  /// A point emitting I = ∫I(λ)dλ in every direction (θo = π).
  std::optional<LightBounds> part_bounds(int part) const override;

  const LightSpectrum* emitted_spectrum() const override { return &intensity_; }

 private:
  Vec3 position_m_;
  LightSpectrum intensity_;
};

/// The irradiance-like "radiance" a delta light at squared distance d² hands to the integrator: I/d², and a
/// unit direction, or std::nullopt when d² is 0 or not finite (shared by point and spot lights).
std::optional<LightSample> delta_position_sample(Vec3 light_position_m, const LightReference& ref,
                                                 SampledSpectrum intensity);

}  // namespace rimu
