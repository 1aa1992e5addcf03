// A measured BRDF (MeasuredBrdf's tables) at a hit, for the path's four wavelengths: reflection only, two-sided.
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"
#include "transport/bsdfs/measured_brdf.h"

namespace rimu {

/// f(ωo, ωi) = max(0, S(u; ωo, λ)) · D(ωm) / (4 σ(ωo) cos θi), the model of MeasuredBrdf, per lane (each lane reads
/// the spectral table at its own wavelength). sample() warps u by the luminance table and then by the visible-normal
/// table into a half vector ωm and reflects ωo about it; its density is the product of the two warps' densities
/// divided by the Jacobian of u → ωm (dω = 2π² u_θ sin θm du, the square's map to the sphere) and of ωm → ωi
/// (4 ωo·ωm), the same in every lane. Both are pbrt-v4's `measured` material's, so a scene renders alike in both.
/// The Jacobian is kept from 0 (at most 10⁶ per unit of u) as pbrt-v4 keeps it, so that a half vector at the pole
/// gives a finite density.
/// Anisotropic tables are oriented by the shading frame's first tangent (pbrt-v4 orients them by ∂p/∂u). The back
/// of the surface sees the BRDF of ωo, ωi turned through the origin (−ωo, −ωi), as in pbrt-v4.
class MeasuredBsdf {
 public:
  MeasuredBsdf(const MeasuredBrdf* brdf, Float4 lambda_nm) : brdf_(brdf), lambda_nm_(lambda_nm) {}

  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// std::nullopt if wo lies on the horizon or the reflected direction falls below it. `u_lobe` is unused.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const { return {false, true, false, brdf_->glossy()}; }

 private:
  /// A direction pair in the tables' terms: both turned to the front, the half vector, ωo's angles, ωm on the square
  /// and the visible-normal warp's inverse there (the spectral table's coordinates and the warp's density).
  struct Pair {
    Vec3 wo, wi, wm;
    float phi_o = 0, theta_o = 0;
    Vec2 u_wm;
    BilinearWarp2D::Sample vndf;
  };
  /// std::nullopt when wo and wi lie on opposite sides, on the horizon, or opposite each other.
  std::optional<Pair> pair_of(Vec3 wo, Vec3 wi) const;
  /// S(u; ωo, λ) per lane, clamped to ≥ 0.
  SampledSpectrum spectral_factor(Vec2 u, float phi_o, float theta_o) const;
  /// D(ωm) / (4 σ(ωo) cos θi).
  float microfacet_factor(Vec2 u_wm, Vec2 u_wo, float cos_theta_i) const;

  const MeasuredBrdf* brdf_;
  Float4 lambda_nm_;
};

}  // namespace rimu
