// A diffuse base under a smooth, clear dielectric coat: plastics, varnished wood, glazed ceramics.
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"

namespace rimu {

/// A Lambertian base of albedo ρ under a smooth, non-absorbing dielectric coat of index η (per lane).
///
/// Model (the layered "plastic" of Weidlich & Wilkie 2007, "Arbitrarily Layered Micro-Facet Surfaces", §4, in
/// the closed form Mitsuba's plastic documents). The coat reflects F(θo) specularly (a delta lobe). The rest
/// enters, reaches the base, and leaves it as uniform radiance; of that, the fraction F̄_int (the coat's
/// hemispherical reflectance from inside) is sent back to the base, again and again, a geometric series. The
/// radiance that escapes through the coat towards wo is multiplied by (1 − F(θo))/η² (radiance changes as n²):
///     f_diffuse(wo, wi) = ρ (1 − F(θi)) (1 − F(θo)) / (π η² (1 − ρ F̄_int)),   1 − F̄_int = (1 − F̄_ext)/η².
/// With ρ = 1 the albedo is F(θo) + (1 − F(θo)) · 1 = 1 exactly: the model conserves energy, and loses it only
/// through ρ < 1. F̄_ext (the coat's reflectance for diffuse light from outside) is passed in, since it costs a
/// quadrature (fresnel_diffuse_reflectance); materials tabulate it over wavelength once.
/// An absorbing coat (optical thickness τ, no scattering: pbrt-v4's coat with albedo 0) stays in closed form:
/// each crossing along the refracted cosine μ attenuates by a(μ) = exp(−τ/μ), so
///     f_diffuse = ρ T(θi) T(θo) a(μi) a(μo) / (π η² (1 − ρ K)),   K = 2∫₀¹ F_int(μ) exp(−2τ/μ) μ dμ,
/// K being the fraction of the base's diffuse light that comes back to it (coat_internal_reflectance); τ = 0
/// gives the clear coat above (K = F̄_int).
/// Neglected: polarisation between bounces (every Fresnel event uses the unpolarised average), the lateral
/// offset of light in a coat of finite thickness (light leaves where it entered), and any roughness of the coat
/// (rough or scattering coats: LayeredBsdf).
///
/// Sampling: the specular lobe with probability p = F / (F + (1 − F) ρ̄), ρ̄ = max(mean of the lanes' ρ, 0.05)
/// (an estimate of the two lobes' shares of the albedo; the floor keeps the diffuse lobe sampled on black bases);
/// otherwise cosine-weighted. Lane k's pdf uses F(θo, η_k); ρ̄ is the same for every hero.
/// Two-sided: wo below the surface is mirrored into the upper hemisphere (and wi with it).
class CoatedDiffuseBsdf {
 public:
  /// `albedo` ρ, coat index `eta` (n_coat / n_outside), and F̄_ext(η) per lane.
  CoatedDiffuseBsdf(SampledSpectrum albedo, SampledSpectrum eta, SampledSpectrum diffuse_fresnel_external);
  /// An absorbing coat of optical thickness `thickness` τ ≥ 0; `internal_reflectance` = K(η, τ) per lane.
  static CoatedDiffuseBsdf absorbing(SampledSpectrum albedo, SampledSpectrum eta, SampledSpectrum internal_reflectance,
                                     float thickness);

  /// The diffuse part of f per lane (the coat's mirror reflection is a delta, not evaluated).
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  /// The density of the diffuse lobe, (1 − p_k) |cos θi| / π per lane.
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// The coat's mirror reflection (if u_lobe < p_hero) or a cosine-weighted diffuse direction.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const { return {true, true, false}; }

 private:
  CoatedDiffuseBsdf() = default;
  SampledSpectrum specular_probability(SampledSpectrum coat_reflectance) const;
  /// T(θ) a(μt) per lane: the coat's transmittance along w times the slab's attenuation along its refraction.
  SampledSpectrum crossing(float cos_theta) const;

  SampledSpectrum albedo_, eta_;
  SampledSpectrum diffuse_scale_;  // ρ / (π η² (1 − ρ K))
  float mean_albedo_ = 0.0f;
  float thickness_ = 0.0f;
};

/// K(η, τ) = 2∫₀¹ F_int(μ) exp(−2τ/μ) μ dμ: the fraction of diffuse light leaving a Lambertian base that the
/// coat (index η ≥ 1 over the base's side) reflects back to it through an absorbing slab of optical thickness τ
/// (F_int: Fresnel from inside, 1 below the critical cosine). Composite Simpson split at the critical cosine
/// (with the substitution of fresnel_diffuse_reflectance above it); error < 1e-6; setup-time cost.
double coat_internal_reflectance(double eta, double thickness);

}  // namespace rimu
