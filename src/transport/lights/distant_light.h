// A distant light (the sun): parallel light of irradiance E(λ) at normal incidence, optionally from a small disc
// of directions.
//
// Zero angular diameter: a delta in direction; the "radiance" handed to the integrator is E, pdf 1, is_delta, so
// a surface tilted by θ receives E cos θ.
//
// Angular diameter δ > 0 (the sun: 0.53°): a uniformly bright disc of directions, the cone of half-angle α = δ/2
// around the axis. Its radiance L must reproduce E at normal incidence:
//   E = ∫_cone L cos θ dω = L · 2π ∫₀^α cos θ sin θ dθ = L · π sin²α,   so   L = E / (π sin²α)
// (equivalently E / (Ω · mean cos θ) with Ω = 2π(1 − cos α) and mean cos θ = (1 + cos α)/2). Because n·ω is linear
// in ω and the cone is symmetric about its axis, a plane tilted by θ (cone fully above its horizon) receives exactly
// E cos θ, as for the delta light. Directions are sampled uniformly in the cone: pdf 1/Ω. 1 − cos α = 2 sin²(α/2)
// is computed in double: for the sun it is 1.07e-5, which float cos α would get 0.5 % wrong.
#pragma once

#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"

namespace rimu {

class DistantLight final : public Light {
 public:
  /// Light arriving from `direction_to_light` (world space, from the scene towards the light; normalised here)
  /// with irradiance `irradiance` W/(m²·nm) on a surface facing it. `angular_diameter_deg` in [0, 180) (asserted);
  /// 0 is a delta light.
  DistantLight(Vec3 direction_to_light, LightSpectrum irradiance, double angular_diameter_deg = 0.0);

  /// Delta: wi = axis, radiance E, pdf 1. Disc: a direction uniform in the cone, radiance L, pdf 1/Ω. distance ∞.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  /// 1/Ω inside the cone, else 0 (always 0 for the delta light). `hit` is ignored.
  float pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit = nullptr) const override;
  /// L inside the cone, else 0 (always 0 for the delta light: a ray cannot hit it).
  SampledSpectrum radiance_escaped(Vec3 direction, const SampledWavelengths& lambda) const override;
  /// The power through a disc of the scene's radius facing the light: π r² ∫E(λ) dλ.
  double total_power_w(double scene_radius_m) const override;
  bool is_delta() const override { return one_minus_cos_alpha_ == 0.0; }
  bool is_infinite() const override { return true; }
  /// ∫E dλ over 360-830 nm, W/m².
  std::optional<float> directional_irradiance_w_m2() const override { return float(irradiance_.integral_360_830()); }

  /// L = E/(π sin²α) per unit of the irradiance spectrum (0 for the delta light).
  double radiance_per_irradiance() const { return radiance_per_irradiance_; }
  /// Ω = 2π(1 − cos α), sr.
  double cone_solid_angle_sr() const;
  /// The direction towards the light's centre (unit, world space).
  Vec3 axis() const { return axis_; }

  const LightSpectrum* emitted_spectrum() const override { return &irradiance_; }

 private:
  bool inside_cone(Vec3 direction) const;

  Vec3 axis_;
  LightSpectrum irradiance_;
  double one_minus_cos_alpha_ = 0.0;
  double radiance_per_irradiance_ = 0.0;
};

}  // namespace rimu
