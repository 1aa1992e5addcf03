// A thin transparent sheet (a window pane, a soap film without interference): both faces are smooth dielectric
// interfaces so close together that light leaves where it entered.
#pragma once

#include <optional>

#include "transport/bsdf_flags.h"
#include "transport/bsdf_sample.h"

namespace rimu {

/// A parallel slab of index η per lane (η = n_sheet / n_outside) in a medium of index 1 on both sides, of
/// negligible thickness. Summing the inter-reflections between the two faces (each with Fresnel reflectance
/// R₀ = F(|cos θo|, η), transmittance T₀ = 1 − R₀), the sheet reflects
///     R = R₀ + T₀² R₀ / (1 − R₀²)      and transmits  T = 1 − R  (lossless; pbrt-v4's ThinDielectricBxDF),
/// both as delta lobes. The transmitted ray leaves parallel to the incident one (wi = −wo): the two refractions
/// cancel, so the direction does not depend on λ even for a dispersive η, and there is no 1/η² radiance
/// scaling (the ray ends in the medium it started in). Symmetric in the side of wo.
///
/// Lobe choice: sample() reflects with probability R(hero) and transmits otherwise; lane k's pdf is R_k or T_k.
class ThinDielectricBsdf {
 public:
  explicit ThinDielectricBsdf(SampledSpectrum eta) : eta_(eta) {}

  /// 0: both lobes are deltas.
  SampledSpectrum eval(Vec3, Vec3) const { return Float4(0.0f); }
  SampledSpectrum pdf(Vec3, Vec3) const { return Float4(0.0f); }
  /// Reflect (mirror) if u_lobe < R(hero), else pass straight through. std::nullopt if wo.z = 0. `u` is unused.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const { return {true, false, true}; }

  /// The sheet's total reflectance R per lane for a ray at |cos θ| = abs_cos_theta (the formula above).
  SampledSpectrum reflectance(float abs_cos_theta) const;
  SampledSpectrum eta() const { return eta_; }

 private:
  SampledSpectrum eta_;
};

}  // namespace rimu
