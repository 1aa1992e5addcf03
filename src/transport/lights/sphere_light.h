// An emissive sphere: uniform spectral radiance L(λ) over its surface, from its outside (or both sides), sampled
// analytically rather than as a tessellated mesh.
//
// Sampling (from a reference point x at distance d from the centre c, radius r):
//   - outside (d > r): a direction uniform in the cone the sphere subtends, sin θmax = r/d:
//     p_ω = 1/(2π(1 − cos θmax)), with 1 − cos θmax = sin²θmax/(1 + cos θmax) so that far, small spheres keep
//     their precision (sin²θmax = 1e-10 at a 1 cm lamp 1 km away). Every direction in the cone meets the near,
//     outward-facing side, so the estimate L cos θ_i / p_ω is bounded by 2π L whatever d: no 1/d² spike when x
//     touches the sphere (a plate a bulb rests on), unlike area sampling;
//   - inside or on the sphere (d ≤ r): a point uniform on its area, p_ω = d_y²/(4π r² |cos θ_l|), d_y the distance
//     to the point, θ_l between its normal and y → x. Only a two-sided sphere lights its inside; a one-sided one
//     returns std::nullopt there (its outward emission never reaches a point on or inside it).
// pdf_li recomputes the same technique's density for a direction from x (it needs no hit: the sphere is intersected
// here), so MIS sees exactly the density the light sample had.
//
// Front side: the outside (SurfaceHit::geometric_normal points away from the centre). An inward-facing (reversed)
// emissive sphere is not this light; the pbrt importer keeps those as meshes.
//
// Cost per sample: one square root and a frame more than a triangle's area sample, and no triangle choice; one
// light tree leaf instead of one per triangle (a tessellated sphere has ~9,000).
#pragma once

#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"

namespace rimu {

class SphereLight final : public Light {
 public:
  /// A sphere of `radius_m` > 0 around `centre_m` (world space) emitting `radiance` W/(m²·sr·nm) from its outside,
  /// or from both sides.
  SphereLight(Vec3 centre_m, float radius_m, LightSpectrum radiance, bool two_sided);

  /// Outside: a direction uniform in the subtended cone; inside (two-sided only): a point uniform on the area.
  /// std::nullopt for a black light, for a point on or inside a one-sided sphere, or where the density is not
  /// finite (a grazing area sample).
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  /// The density of sample_li for wi; 0 where wi misses the sphere or sample_li returns nothing. `hit` is not
  /// needed (the sphere is intersected along wi).
  float pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit = nullptr) const override;
  /// L on the emitting side(s): outside when hit.geometric_normal · w_out > 0.
  SampledSpectrum radiance(const SurfaceHit& hit, Vec3 w_out, const SampledWavelengths& lambda) const override;
  /// Lambertian emitter: Φ = π · 4π r² · ∫L(λ) dλ per emitting side.
  double total_power_w(double scene_radius_m) const override;
  bool samples_emission() const override;
  std::optional<EmissionSample> sample_emission(float u_part, Vec2 u_position, Vec2 u_direction,
                                                const SampledWavelengths& lambda) const override;
  EmissionDensity emission_density(Vec3 normal, Vec3 direction) const override;
  /// The sphere's box, every normal (θo = π, θe = π/2) and the intensity πr²·∫L dλ it shows in every direction.
  std::optional<LightBounds> part_bounds(int part) const override;

  const LightSpectrum* emitted_spectrum() const override { return &radiance_; }

  Vec3 centre_m() const { return centre_m_; }
  std::optional<Vec3> emission_centre_m(int) const override {
    return radiance_.is_black() ? std::nullopt : std::optional<Vec3>(centre_m_);
  }
  float radius_m() const { return radius_m_; }
  double area_m2() const;
  bool two_sided() const { return two_sided_; }

 private:
  Vec3 centre_m_;
  float radius_m_;
  LightSpectrum radiance_;
  bool two_sided_;
};

}  // namespace rimu
