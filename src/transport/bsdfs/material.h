// Materials: what a surface is made of, turned into a BSDF at a hit for the path's wavelengths.
#pragma once

#include <memory>
#include <variant>

#include "spectral/library/optical_constants.h"
#include "spectral/spectra/spectrum.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/textures/float_texture.h"
#include "transport/textures/material_context.h"
#include "transport/textures/shading_normal_map.h"
#include "transport/textures/spectral_texture.h"

namespace rimu {

/// Lambertian: reflectance ρ(λ) (clamped to [0, 1] per lane: values above 1 would create energy).
class DiffuseMaterial {
 public:
  explicit DiffuseMaterial(SpectralTexturePtr reflectance);
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  SpectralTexturePtr reflectance_;
};

/// A metal with measured (or given) n(λ), k(λ); smooth when roughness is 0, else GGX with α = roughness².
/// Roughness may vary over the surface (a FloatTexture, clamped to [0, 1] per hit).
class ConductorMaterial {
 public:
  /// Throws InputError if a roughness is outside [0, 1] or a spectrum is missing.
  ConductorMaterial(ComplexIorSpectra ior, float roughness_u, float roughness_v);
  ConductorMaterial(ComplexIorSpectra ior, float roughness) : ConductorMaterial(std::move(ior), roughness, roughness) {}
  /// Textured roughness along the two tangents. Throws InputError if an input is missing.
  ConductorMaterial(ComplexIorSpectra ior, FloatTexturePtr roughness_u, FloatTexturePtr roughness_v);
  /// pbrt-v4's artist-friendly conductor: a normal-incidence reflectance r(λ), met with n = 1 and
  /// k = 2·√(r/(1 − r)) (which gives exactly r at normal incidence: ((n−1)² + k²)/((n+1)² + k²) = k²/(4 + k²)),
  /// r clamped to [0, 0.9999] per hit as pbrt does. Throws InputError if an input is missing.
  static ConductorMaterial from_reflectance(SpectralTexturePtr reflectance, FloatTexturePtr roughness_u,
                                            FloatTexturePtr roughness_v);
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  ConductorMaterial() : distribution_(0.0f, 0.0f) {}
  TrowbridgeReitz distribution_at(const MaterialContext& context) const;

  ComplexIorSpectra ior_;
  SpectralTexturePtr reflectance_;               // instead of ior_ (from_reflectance)
  FloatTexturePtr roughness_u_, roughness_v_;    // null: distribution_ everywhere
  TrowbridgeReitz distribution_;
};

/// Glass, water: index of refraction n(λ) (a SellmeierSpectrum disperses; a ConstantSpectrum does not) against
/// an outside of index 1; smooth when roughness is 0, else GGX with α = roughness².
class DielectricMaterial {
 public:
  /// Throws InputError if roughness is outside [0, 1], the spectrum is missing, or n ≤ 0 somewhere.
  DielectricMaterial(SpectrumPtr ior, float roughness);
  /// Textured roughness along the two tangents (clamped to [0, 1] per hit). Throws as above.
  DielectricMaterial(SpectrumPtr ior, FloatTexturePtr roughness_u, FloatTexturePtr roughness_v);
  /// Light enters diffusely (DielectricBsdf, "Diffuse entry"): for the boundary of a subsurface medium.
  void use_diffuse_entry();
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  SpectrumPtr ior_;
  FloatTexturePtr roughness_u_, roughness_v_;  // null: distribution_ everywhere
  TrowbridgeReitz distribution_;
  /// DielectricBsdf::diffuse_entry_normalisation of n(λ), tabulated at load; null without diffuse entry.
  SpectrumPtr diffuse_entry_normalisation_;
};

/// Lambertian reflection R(λ) and transmission T(λ), both multiplied by `scale` (pbrt-v4's diffusetransmission).
/// Per lane R and T are clamped to [0, 1] and, where R + T > 1 (which would create energy), both are divided by
/// R + T: the ratio R : T is kept, the sheet scatters everything. pbrt-v4 does not rescale (it renders such a
/// surface brighter than physical).
class DiffuseTransmissionMaterial {
 public:
  /// Throws InputError if a texture is missing or scale < 0.
  DiffuseTransmissionMaterial(SpectralTexturePtr reflectance, SpectralTexturePtr transmittance, float scale);
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  SpectralTexturePtr reflectance_;
  SpectralTexturePtr transmittance_;
  float scale_;
};

/// pbrt-v4's "hair": a fibre scattering by Chiang et al. 2016 (HairBsdf), with absorption σa(λ) per unit of the
/// fibre's radius, or σa derived per wavelength from a desired colour (`from_reflectance`, Chiang et al. Eq. 9).
/// At each hit the fibre's direction is the hit's ∂p/∂u (a curve's tangent) and h = 2v − 1 across its width
/// (MaterialContext::uv.y); on a surface without ∂p/∂u the shading frame's first axis stands in
/// (hair_fibre_direction).
class HairMaterial {
 public:
  /// Throws InputError if sigma_a is missing, or η < 1, β_m or β_n outside (0, 1], or |α| > 45°.
  HairMaterial(SpectrumPtr sigma_a, HairParameters parameters);
  /// σa from the fibre colour c(λ) (clamped to [1e-4, 1] per lane) and β_n. Throws as above.
  static HairMaterial from_reflectance(SpectrumPtr reflectance, HairParameters parameters);
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;
  const HairParameters& parameters() const { return parameters_; }

 private:
  HairMaterial(SpectrumPtr sigma_a, SpectrumPtr reflectance, HairParameters parameters);

  SpectrumPtr sigma_a_;
  SpectrumPtr reflectance_;  // instead of sigma_a_ (from_reflectance)
  HairParameters parameters_;
};

/// A thin sheet of glass of index n(λ) in air (ThinDielectricBsdf): smooth only, as in pbrt-v4. Optionally tinted:
/// `internal_transmittance` τₙ(λ) is what one pass through the glass at normal incidence keeps (absorption only,
/// the surface reflections not included; null: clear). Shadow rays pass it (docs/transport.md, "Glazing").
class ThinDielectricMaterial {
 public:
  /// Throws InputError if the spectrum is missing or n ≤ 0 somewhere.
  explicit ThinDielectricMaterial(SpectrumPtr ior, SpectrumPtr internal_transmittance = nullptr);
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  SpectrumPtr ior_;
  SpectrumPtr internal_transmittance_;
};

/// A coat's layer parameters beyond its index: roughness of its surface, the slab under it (LayeredBsdf's
/// LayerMedium, with a textured albedo) and the random walk's limits.
struct CoatLayer {
  float roughness = 0.0f;             ///< perceptual, α = r² (isotropic)
  /// A roughness that varies over the surface instead of `roughness` (null: `roughness` everywhere); clamped to
  /// [0, 1] per hit. pbrt-v4 scenes texture their coats' roughness (zero-day: 22 coated materials).
  FloatTexturePtr roughness_texture;
  float thickness = 0.0f;     ///< in mean free paths (σt = 1)
  SpectralTexturePtr albedo;  ///< single-scattering albedo of the slab; null = 0 (clear: absorbing only)
  float g = 0.0f;             ///< Henyey-Greenstein asymmetry of the slab
  LayerWalk walk;
  /// The slab only absorbs (no albedo, or zero thickness).
  bool clear() const { return thickness == 0.0f || !albedo; }
  /// The coat's roughness at a hit.
  float roughness_at(const MaterialContext& context) const;
};

/// A Lambertian base of reflectance ρ(λ) under a dielectric coat of index n(λ).
/// Rule: a smooth coat whose slab does not scatter (no albedo given, or zero thickness) uses the exact closed
/// form (CoatedDiffuseBsdf, absorbing when thickness > 0: fast, noiseless); any other coat (rough, or a scattering
/// slab) the stochastic LayeredBsdf, with the coat index of the hero wavelength for the whole walk (the coat's
/// dispersion, ~1 % in n for lacquers and glasses, is neglected there). Under a textured roughness the rule is
/// applied per hit: the closed form where the texture reads 0.
/// The closed form's internal reflectance K(n(λ), thickness) is tabulated at 5 nm at construction (a smooth
/// function of n, which varies by about 1% over the visible for glasses).
class CoatedDiffuseMaterial {
 public:
  /// Throws InputError if the coat index is not ≥ 1 over 360-830 nm, an input is missing, the roughness is
  /// outside [0, 1], the thickness negative, |g| ≥ 1, or max_depth/samples < 1.
  CoatedDiffuseMaterial(SpectralTexturePtr reflectance, SpectrumPtr coat_ior, CoatLayer layer = {});
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  SpectralTexturePtr reflectance_;
  SpectrumPtr coat_ior_;
  SpectrumPtr coat_internal_reflectance_;  // K(n(λ), thickness) of the closed form
  CoatLayer layer_;
};

/// A conductor of complex index n(λ) + ik(λ) (smooth or GGX) under a dielectric coat of index n_c(λ) with a
/// slab (pbrt-v4's coatedconductor): always the stochastic LayeredBsdf. The metal's index is taken relative to
/// the coat, (n + ik)/n_c, and the coat index is the hero wavelength's for the whole walk (as above).
class CoatedConductorMaterial {
 public:
  /// Throws InputError for a missing input, a coat index below 1, roughnesses outside [0, 1], a negative
  /// thickness, |g| ≥ 1 or max_depth/samples < 1.
  CoatedConductorMaterial(SpectrumPtr coat_ior, ComplexIorSpectra conductor, float conductor_roughness_u,
                          float conductor_roughness_v, CoatLayer layer);
  /// pbrt-v4's artist metal under the coat: the conductor's normal-incidence reflectance r(λ) (clamped to
  /// [0, 0.9999]) met with n = 1, k = 2√(r/(1 − r)) as ConductorMaterial::from_reflectance, both then divided by
  /// the coat's index (the metal borders the coat). Throws as the other constructor.
  CoatedConductorMaterial(SpectrumPtr coat_ior, SpectralTexturePtr conductor_reflectance, float conductor_roughness_u,
                          float conductor_roughness_v, CoatLayer layer);
  /// The conductor's roughness varies over the surface (each texture clamped to [0, 1] per hit; pbrt-v4's
  /// textured conductor.roughness). Either form of the metal; throws as the constructors above and if a roughness
  /// texture is missing.
  CoatedConductorMaterial with_conductor_roughness(FloatTexturePtr roughness_u, FloatTexturePtr roughness_v) &&;
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  /// Both public constructors: `reflectance` (by_reflectance) or `conductor`'s n and k, checked in one order.
  CoatedConductorMaterial(SpectrumPtr coat_ior, ComplexIorSpectra conductor, SpectralTexturePtr reflectance,
                          float conductor_roughness_u, float conductor_roughness_v, CoatLayer layer,
                          bool by_reflectance);

  SpectrumPtr coat_ior_;
  ComplexIorSpectra conductor_;
  SpectralTexturePtr reflectance_;  // instead of conductor_ (artist metal)
  TrowbridgeReitz conductor_distribution_;
  FloatTexturePtr conductor_roughness_u_, conductor_roughness_v_;  // null: conductor_distribution_ everywhere
  CoatLayer layer_;
};

/// A measured BRDF of the RGL database (pbrt-v4's `measured`): MeasuredBsdf over tables read once at load and
/// shared by every surface that names the same file.
class MeasuredMaterial {
 public:
  /// Throws InputError if the tables are missing.
  explicit MeasuredMaterial(MeasuredBrdfPtr brdf);
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;
  const MeasuredBrdf& brdf() const { return *brdf_; }

 private:
  MeasuredBrdfPtr brdf_;
};

class Material;

/// pbrt-v4's "mix": at each hit one of two materials, `second` with probability amount(hit) ∈ [0, 1] (clamped),
/// else `first`. The choice uses a hash of the hit (MaterialContext::hash, salted so that nested mixes choose
/// independently), not the sampler: the same point seen from the same direction always gets the same material,
/// so next-event estimation and the continuation ray at a vertex use one BSDF (they do anyway in Rimu's
/// integrators, which build one BSDF per vertex), and a mix is a per-point choice of material, i.e. a 50/50 mix
/// renders as the average of the two images.
class MixMaterial {
 public:
  /// Throws InputError if a material or the amount is missing.
  MixMaterial(std::shared_ptr<const Material> first, std::shared_ptr<const Material> second, FloatTexturePtr amount,
              uint32_t salt);
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const;
  /// The material used at this hit (a nested mix is resolved further by its own bsdf()).
  const Material& choose(const MaterialContext& context) const;
  /// Whether either material reads ∂p/∂u, ∂p/∂v (Material::uses_tangents).
  bool uses_tangents() const;

 private:
  std::shared_ptr<const Material> first_, second_;
  FloatTexturePtr amount_;
  uint32_t salt_;
};

/// A surface material of any kind, held by value (a std::variant): a scene keeps a std::vector<Material>.
/// Built once at scene load (where invalid parameters throw InputError); bsdf() is called per hit from many
/// threads, evaluates the spectral inputs at the path's wavelengths and returns the BSDF by value (no allocation).
/// Roughness parameters are perceptual, r ∈ [0, 1], with α = r² (TrowbridgeReitz::roughness_to_alpha).
class Material {
 public:
  using Variant = std::variant<DiffuseMaterial, ConductorMaterial, DielectricMaterial, CoatedDiffuseMaterial,
                               ThinDielectricMaterial, DiffuseTransmissionMaterial, CoatedConductorMaterial, MixMaterial,
                               HairMaterial, MeasuredMaterial>;

  template <typename T>
  Material(T material) : material_(std::move(material)) {}  // NOLINT(google-explicit-constructor)

  /// The BSDF at the surface point `context` for the four wavelengths of the path.
  Bsdf bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
    return std::visit([&](const auto& m) { return m.bsdf(context, lambda); }, material_);
  }
  const Variant& variant() const { return material_; }
  /// Whether shadow rays pass this material straight through, weighted by its transmittance (a thin dielectric:
  /// its transmission does not bend rays; docs/transport.md, "Glazing"). Refracting and rough materials block them.
  bool passes_shadow_rays() const { return std::holds_alternative<ThinDielectricMaterial>(material_); }
  /// A `mix`: which material it is at a hit depends on the direction it is seen from (MaterialContext::hash).
  bool is_stochastic_mix() const { return std::holds_alternative<MixMaterial>(material_); }

  /// Gives the material a normal or bump map (null: none). A mix's own modifier is ignored: the chosen
  /// material's applies (pbrt-v4's mix has none).
  void set_normal_modifier(std::shared_ptr<const ShadingNormalModifier> modifier) { normal_modifier_ = std::move(modifier); }
  bool has_normal_modifier() const { return normal_modifier_ != nullptr; }
  /// Whether a hit on this material needs ∂p/∂u, ∂p/∂v (a normal or bump map, hair's fibre direction, here or in a
  /// mix's materials): the scene computes them only then (EmbreeScene::set_surface_tangents).
  bool uses_tangents() const;
  /// The shading normal the BSDF is to be built around: the hit's, or the normal/bump map's (unit, on the geometric
  /// normal's side). Integrators call this before bsdf() and pass the result in the context and shading frame.
  Vec3 shading_normal(const MaterialContext& context) const;

 private:
  Variant material_;
  std::shared_ptr<const ShadingNormalModifier> normal_modifier_;
};

}  // namespace rimu
