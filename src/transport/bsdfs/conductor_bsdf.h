// A metal: specular reflection with complex Fresnel, smooth (mirror) or rough (GGX microfacets).
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"
#include "transport/bsdfs/microfacet.h"

namespace rimu {

/// Reflection from a conductor with complex index n + ik per lane.
///
/// Rough (Cook-Torrance with GGX; Walter et al. 2007, Eq. 20, with Heitz 2014's height-correlated G2):
///     f(wo, wi) = D(h) G2(wo, wi) F(wo·h) / (4 cos θo cos θi),   h = (wo + wi)/|wo + wi|,
/// sampled with visible normals, pdf = D_wo(h) / (4 wo·h) (the Jacobian of reflection, Walter et al. Eq. 14).
/// Only the Fresnel factor depends on λ, so the pdf is equal in all lanes.
/// Smooth (α below TrowbridgeReitz::kSmoothAlpha): a delta mirror with f·cos θi = F(cos θo), pdf 1.
/// Single scattering only: the energy of light bounced more than once between microfacets is lost (a few % at
/// α ≈ 0.5, more at grazing angles).
/// Two-sided: wo below the surface is mirrored into the upper hemisphere (and wi with it).
class ConductorBsdf {
 public:
  ConductorBsdf(SampledSpectrum n, SampledSpectrum k, TrowbridgeReitz distribution)
      : n_(n), k_(k), distribution_(distribution) {}

  /// f per lane (0 for the smooth mirror, whose lobe is a delta, and when wo, wi are on opposite sides).
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  /// Solid-angle density of sample(), equal in all lanes; 0 for the smooth mirror.
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// The mirror direction (smooth) or a visible-normal sample (rough). std::nullopt if wo is on the horizon or
  /// the reflected direction falls below it. `u_lobe` is unused.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const {
    const bool smooth = distribution_.effectively_smooth();
    return {smooth, !smooth, false, distribution_.is_glossy()};
  }

 private:
  SampledSpectrum fresnel(float cos_theta) const;

  SampledSpectrum n_, k_;
  TrowbridgeReitz distribution_;
};

}  // namespace rimu
