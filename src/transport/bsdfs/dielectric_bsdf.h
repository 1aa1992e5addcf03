// A transparent interface (glass, water): Fresnel-weighted reflection and refraction, smooth or rough (GGX),
// with a wavelength-dependent index of refraction.
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"
#include "transport/bsdfs/microfacet.h"

namespace rimu {

/// The interface between the outside (index 1, the side of +z) and a dielectric of relative index η per lane
/// (η = n_inside / n_outside). wo.z < 0 means the path is inside the dielectric.
///
/// Lobe choice: sample() reflects with probability R = F(wo, η_hero) and refracts otherwise. Lane k's pdf is the
/// density had λ_k been the hero, so it uses F(·, η_k): the lanes' pdfs differ by their Fresnel factors.
///
/// Smooth (α < TrowbridgeReitz::kSmoothAlpha): two delta lobes. Reflection: f·cos θi = R per lane, pdf = R.
/// Refraction: wi follows Snell's law with the hero's η. Lanes with a different η would have refracted
/// elsewhere, so their f and pdf are 0 and the sample has wavelength_dependent_direction set; lanes with the
/// same η (a constant index) keep f·cos θi = T/η'², pdf = T (T = 1 − F).
///
/// Rough (Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", Eqs. 16-21, with
/// visible-normal sampling and height-correlated G2): with η' = n_i/n_o the index ratio across the interface
/// along wo → wi (1 for reflection) and the generalised half vector m ∝ wo + η' wi,
///     reflection:  f = D(m) G2 F / (4 |cos θo cos θi|),            pdf = D_wo(m) / (4 |wo·m|) · F
///     refraction:  f = (1−F) D(m) G2 |wi·m| |wo·m| / (|cos θo cos θi| (wi·m + wo·m/η')²) / η'²,
///                  pdf = D_wo(m) |wi·m| / (wi·m + wo·m/η')² · (1−F).
/// Every lane is evaluated with its own η (its own m), so rough refraction is not a dispersive delta event:
/// all four lanes keep valid f and pdf.
///
/// Radiance scaling: camera paths carry radiance, and radiance crossing into a medium of index n changes as n²
/// (Veach 1997, §5.2, "non-symmetric scattering due to refraction"). The 1/η'² factor above applies it, so f is
/// the BSDF for radiance transport, satisfying f(wo, wi)/n_o² = f(wi, wo)/n_i² (n_o, n_i: the indices on wo's and
/// wi's sides; Veach 1997, Eq. 5.14). A light-tracing (importance) path would omit it; Rimu has none.
///
/// Diffuse entry (optional; the boundary of a subsurface medium): light from the outside enters diffusely instead
/// of by refraction, as pbrt-v4's subsurface material (its BSSRDF's exit lobe S_ω, after Christensen & Burley 2015)
/// and Cycles' random walk assume. Seen from the outside nothing changes (the lobes above); a path inside
/// (wo.z < 0) is mirrored with F(wo) (a smooth inside, whatever the roughness) or leaves through the lobe
///     f(wo, wi) = (1 − F(wo)) (1 − F(wi)) / (π (1 − F̄_int)),   wi.z > 0,
/// with F̄_int = 1 − (1 − F̄_ext(η))/η² the inside's hemispherical reflectance (fresnel.h). It is non-delta, so
/// next-event estimation reaches every light from the boundary, point, spot and distant ones included, which a
/// smooth refracting boundary never lets in. Its normalisation makes the boundary exact in a white furnace: a
/// non-absorbing medium under uniform radiance L holds η²L inside and shows L outside (tests/transport/
/// media_slab_reference_test.cpp; the lobe's integral in bsdf_energy_test.cpp, its sampling in
/// bsdf_chi_square_test.cpp). sample() draws wi from the cosine and weights by the rest; s.eta = 1/η
/// (f carries η² on leaving, as refraction out would).
class DielectricBsdf {
 public:
  DielectricBsdf(SampledSpectrum eta, TrowbridgeReitz distribution) : eta_(eta), distribution_(distribution) {}
  /// With diffuse entry: `diffuse_entry_normalisation` = 1/(π (1 − F̄_int)) per lane
  /// (diffuse_entry_normalisation(η) of each lane's η).
  DielectricBsdf(SampledSpectrum eta, TrowbridgeReitz distribution, SampledSpectrum diffuse_entry_normalisation)
      : eta_(eta), distribution_(distribution), entry_norm_(diffuse_entry_normalisation), diffuse_entry_(true) {}
  /// 1/(π (1 − F̄_int(η))) for a dielectric of relative index η: what makes the diffuse entry lobe conserve flux.
  /// Setup-time cost (fresnel_diffuse_reflectance).
  static double diffuse_entry_normalisation(double eta);

  /// f per lane (radiance transport); 0 for the smooth interface (delta lobes only).
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  /// Per-lane solid-angle density of sample(): lane k as if λ_k were the hero; 0 for the smooth interface.
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// eval(wo, wi), and pdf(wi, wo) (the density of sampling wo from wi) in `pdf_reverse`, from one evaluation of
  /// the shared microfacet terms: the half vector, D and G are the same both ways. For walks that leave through
  /// the interface and weigh that against arriving from the other side (the layered BSDF).
  SampledSpectrum eval_with_reverse_pdf(Vec3 wo, Vec3 wi, SampledSpectrum& pdf_reverse) const;
  /// Reflect if u_lobe < F(hero), else refract; `u` picks the microfacet normal (rough only). std::nullopt if
  /// wo.z = 0, or the sampled direction is invalid (rough: reflected through the surface, or on the horizon).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const {
    const bool smooth = is_smooth();
    if (diffuse_entry_) return {true, true, true};  // the inside's mirror is a delta, its way out is not
    return {smooth, !smooth, true, !smooth && distribution_.is_glossy()};
  }

  SampledSpectrum eta() const { return eta_; }

 private:
  /// Delta lobes when the microfacets are too narrow to resolve, or when η = 1 in every lane (no interface).
  bool is_smooth() const { return distribution_.effectively_smooth() || (eta_ == Float4(1.0f)).all(); }
  std::optional<BsdfSample> sample_smooth(Vec3 wo, float u_lobe) const;
  /// Diffuse entry, seen from the inside (wo.z < 0): the mirror or the way out.
  std::optional<BsdfSample> sample_inside_diffuse_entry(Vec3 wo, float u_lobe, Vec2 u) const;
  SampledSpectrum eval_inside_diffuse_entry(Vec3 wo, Vec3 wi) const;
  SampledSpectrum pdf_inside_diffuse_entry(Vec3 wo, Vec3 wi) const;
  /// f and pdf of the rough interface for one lane's η, and pdf(wi, wo) if `pdf_reverse` is given.
  void eval_rough_lane(Vec3 wo, Vec3 wi, float eta, float& f, float& pdf, float* pdf_reverse = nullptr) const;
  /// The same per lane (each lane with its own η; computed once when all lanes share one η).
  void eval_rough(Vec3 wo, Vec3 wi, SampledSpectrum& f, SampledSpectrum& pdf, SampledSpectrum* pdf_reverse = nullptr) const;

  SampledSpectrum eta_;
  TrowbridgeReitz distribution_;
  SampledSpectrum entry_norm_{0.0f};
  bool diffuse_entry_ = false;
};

/// The refraction of w (unit, on the side of unit normal n: w·n > 0) through an interface of index ratio
/// eta_ratio = n_transmitted / n_incident, by Snell's law; std::nullopt under total internal reflection.
std::optional<Vec3> refract(Vec3 w, Vec3 n, float eta_ratio);

}  // namespace rimu
