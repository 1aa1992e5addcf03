// A thin transparent sheet (a window pane, a soap film without interference): both faces are smooth dielectric
// interfaces so close together that light leaves where it entered.
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"

namespace rimu {

/// A parallel slab of index η per lane (η = n_sheet / n_outside) in a medium of index 1 on both sides, of
/// negligible thickness. Summing the inter-reflections between the two faces (each with Fresnel reflectance
/// R₀ = F(|cos θo|, η), transmittance T₀ = 1 − R₀) with τ the internal transmittance of one pass through the glass,
///     R = R₀ + T₀² R₀ τ² / (1 − R₀² τ²)      and      T = T₀² τ / (1 − R₀² τ²),
/// per polarisation (R₀ = r_s² or r_p²), then averaged (unpolarised light), both as delta lobes. A clear sheet
/// (τ = 1) is lossless, T = 1 − R (pbrt-v4's ThinDielectricBxDF sums the series once with the averaged R₀, which
/// differs at oblique incidence: 1.4 % less T at 60°, 2.9 % at 70° for η = 1.5). A tinted
/// one has τ = τₙ^(1/cos θt): τₙ(λ) is its internal transmittance at normal incidence and the path through the
/// glass grows as 1/cos θt (Beer-Lambert), θt the refraction angle inside. The transmitted ray leaves parallel to
/// the incident one (wi = −wo): the two refractions cancel, so the direction does not depend on λ even for a
/// dispersive η, and there is no 1/η² radiance scaling (the ray ends in the medium it started in). Symmetric in
/// the side of wo.
///
/// Lobe choice: sample() reflects with probability R/(R + T) of the hero and transmits otherwise; lane k's pdf is
/// Rₖ/(Rₖ + Tₖ) or Tₖ/(Rₖ + Tₖ) (for a clear sheet simply Rₖ or Tₖ).
class ThinDielectricBsdf {
 public:
  explicit ThinDielectricBsdf(SampledSpectrum eta) : eta_(eta) {}
  /// A tinted sheet: `internal_transmittance` τₙ per lane, clamped to [0, 1].
  ThinDielectricBsdf(SampledSpectrum eta, SampledSpectrum internal_transmittance);

  /// 0: both lobes are deltas.
  SampledSpectrum eval(Vec3, Vec3) const { return Float4(0.0f); }
  SampledSpectrum pdf(Vec3, Vec3) const { return Float4(0.0f); }
  /// Reflect (mirror) if u_lobe < R/(R + T) of the hero, else pass straight through. std::nullopt if wo.z = 0 or
  /// the sheet neither reflects nor transmits. `u` is unused.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const { return {true, false, true}; }

  /// The sheet's total reflectance R per lane for a ray at |cos θ| = abs_cos_theta (the formula above).
  SampledSpectrum reflectance(float abs_cos_theta) const;
  /// The straight-through lobe at |cos θ| = abs_cos_theta: its weight T per lane (f·|cos θi|, what a ray passing
  /// the sheet is multiplied by) and the per-lane probability that sample() chooses it.
  struct StraightThrough {
    SampledSpectrum transmittance;
    SampledSpectrum probability;
  };
  StraightThrough straight_through(float abs_cos_theta) const;
  SampledSpectrum eta() const { return eta_; }

 private:
  struct Lobes {
    SampledSpectrum r, t;
  };
  Lobes lobes(float abs_cos_theta) const;

  SampledSpectrum eta_;
  std::optional<SampledSpectrum> internal_transmittance_;  // τₙ; none: clear (lossless)
};

}  // namespace rimu
