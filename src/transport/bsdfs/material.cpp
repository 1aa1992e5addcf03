#include "transport/bsdfs/material.h"

#include <cmath>
#include <vector>

#include "spectral/error.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "spectral/wavelengths/wavelength_range.h"
#include "transport/bsdfs/fresnel.h"

namespace rimu {
namespace {

void check_roughness(float roughness, const char* what) {
  if (!(roughness >= 0.0f && roughness <= 1.0f))
    throw InputError({}, std::string(what) + " must lie in [0, 1], got " + std::to_string(roughness));
}

TrowbridgeReitz distribution_for(float roughness_u, float roughness_v) {
  return TrowbridgeReitz(TrowbridgeReitz::roughness_to_alpha(roughness_u),
                         TrowbridgeReitz::roughness_to_alpha(roughness_v));
}

// A textured roughness, known only per hit: into [0, 1] (NaN → 0: fmax returns the number).
float clamp_roughness(float r) { return std::fmin(1.0f, std::fmax(0.0f, r)); }

Float4 clamp_unit(Float4 x) { return clamp(x, Float4(0.0f), Float4(1.0f)); }

/// The smallest value of `s` on a 1 nm grid over the transported range (for load-time validation).
double min_over_range(const Spectrum& s) {
  double lowest = s.value(kLambdaMinNm);
  for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 1.0) lowest = std::min(lowest, s.value(l));
  return lowest;
}

}  // namespace

DiffuseMaterial::DiffuseMaterial(SpectralTexturePtr reflectance) : reflectance_(std::move(reflectance)) {
  if (!reflectance_) throw InputError({}, "a diffuse material needs a reflectance");
}

Bsdf DiffuseMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  return DiffuseBsdf(clamp_unit(reflectance_->evaluate_at(context, lambda)));
}

ConductorMaterial::ConductorMaterial(ComplexIorSpectra ior, float roughness_u, float roughness_v)
    : ior_(std::move(ior)), distribution_(distribution_for(roughness_u, roughness_v)) {
  if (!ior_.n || !ior_.k) throw InputError({}, "a conductor needs both n and k spectra");
  check_roughness(roughness_u, "conductor roughness");
  check_roughness(roughness_v, "conductor roughness");
}

ConductorMaterial::ConductorMaterial(ComplexIorSpectra ior, FloatTexturePtr roughness_u, FloatTexturePtr roughness_v)
    : ior_(std::move(ior)), roughness_u_(std::move(roughness_u)), roughness_v_(std::move(roughness_v)),
      distribution_(0.0f, 0.0f) {
  if (!ior_.n || !ior_.k) throw InputError({}, "a conductor needs both n and k spectra");
  if (!roughness_u_ || !roughness_v_) throw InputError({}, "a conductor needs both roughness textures");
}

ConductorMaterial ConductorMaterial::from_reflectance(SpectralTexturePtr reflectance, FloatTexturePtr roughness_u,
                                                      FloatTexturePtr roughness_v) {
  if (!reflectance || !roughness_u || !roughness_v)
    throw InputError({}, "a conductor by reflectance needs a reflectance and both roughness textures");
  ConductorMaterial m;
  m.reflectance_ = std::move(reflectance);
  m.roughness_u_ = std::move(roughness_u);
  m.roughness_v_ = std::move(roughness_v);
  return m;
}

TrowbridgeReitz ConductorMaterial::distribution_at(const MaterialContext& context) const {
  if (!roughness_u_) return distribution_;
  return distribution_for(clamp_roughness(roughness_u_->evaluate(context)), clamp_roughness(roughness_v_->evaluate(context)));
}

Bsdf ConductorMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  if (reflectance_) {
    const Float4 r = clamp(reflectance_->evaluate_at(context, lambda), Float4(0.0f), Float4(0.9999f));
    const Float4 k = Float4(2.0f) * sqrt(r / (Float4(1.0f) - r));
    return ConductorBsdf(Float4(1.0f), k, distribution_at(context));
  }
  return ConductorBsdf(ior_.n->sample(lambda), ior_.k->sample(lambda), distribution_at(context));
}

DielectricMaterial::DielectricMaterial(SpectrumPtr ior, float roughness)
    : ior_(std::move(ior)), distribution_(distribution_for(roughness, roughness)) {
  if (!ior_) throw InputError({}, "a dielectric needs an index of refraction");
  check_roughness(roughness, "dielectric roughness");
  if (!(min_over_range(*ior_) > 0.0))
    throw InputError({}, "the index of refraction of " + ior_->describe() + " must be positive over 360-830 nm");
}

DielectricMaterial::DielectricMaterial(SpectrumPtr ior, FloatTexturePtr roughness_u, FloatTexturePtr roughness_v)
    : DielectricMaterial(std::move(ior), 0.0f) {
  if (!roughness_u || !roughness_v) throw InputError({}, "a dielectric needs both roughness textures");
  roughness_u_ = std::move(roughness_u);
  roughness_v_ = std::move(roughness_v);
}

void DielectricMaterial::use_diffuse_entry() {
  if (const auto* constant = dynamic_cast<const ConstantSpectrum*>(ior_.get())) {
    diffuse_entry_normalisation_ = std::make_shared<ConstantSpectrum>(
        DielectricBsdf::diffuse_entry_normalisation(constant->value(560.0)));
    return;
  }
  // Every 5 nm: n(λ) of a glass or water changes by < 0.1 % between knots, the normalisation by less.
  std::vector<double> lambda_nm, values;
  for (int nm = 360; nm <= 830; nm += 5) {
    lambda_nm.push_back(nm);
    values.push_back(DielectricBsdf::diffuse_entry_normalisation(ior_->value(nm)));
  }
  diffuse_entry_normalisation_ = std::make_shared<TabulatedSpectrum>(
      std::move(lambda_nm), std::move(values), Extrapolation::clamp, "diffuse entry of " + ior_->describe());
}

Bsdf DielectricMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const TrowbridgeReitz distribution =
      roughness_u_ ? distribution_for(clamp_roughness(roughness_u_->evaluate(context)),
                                      clamp_roughness(roughness_v_->evaluate(context)))
                   : distribution_;
  if (diffuse_entry_normalisation_)
    return DielectricBsdf(ior_->sample(lambda), distribution, diffuse_entry_normalisation_->sample(lambda));
  return DielectricBsdf(ior_->sample(lambda), distribution);
}

DiffuseTransmissionMaterial::DiffuseTransmissionMaterial(SpectralTexturePtr reflectance, SpectralTexturePtr transmittance,
                                                         float scale)
    : reflectance_(std::move(reflectance)), transmittance_(std::move(transmittance)), scale_(scale) {
  if (!reflectance_ || !transmittance_)
    throw InputError({}, "a diffuse transmission material needs a reflectance and a transmittance");
  if (!(scale_ >= 0.0f)) throw InputError({}, "scale must be at least 0, got " + std::to_string(scale_));
}

HairMaterial::HairMaterial(SpectrumPtr sigma_a, SpectrumPtr reflectance, HairParameters parameters)
    : sigma_a_(std::move(sigma_a)), reflectance_(std::move(reflectance)), parameters_(parameters) {
  if (!sigma_a_ && !reflectance_) throw InputError({}, "a hair material needs sigma_a or a reflectance");
  // η < 1 would make the fibre's Bravais index undefined at grazing angles; β = 0 is a variance of 0 (a delta
  // lobe, which this glossy model cannot represent); the paper's mapping is fitted for β ≤ 1. Tilts beyond 45°
  // would fold the TRT lobe (4α) past the pole.
  if (!(parameters_.eta >= 1.0f && std::isfinite(parameters_.eta)))
    throw InputError({}, "hair eta must be a finite number ≥ 1, got " + std::to_string(parameters_.eta));
  for (const auto& [value, name] : {std::pair{parameters_.beta_m, "beta_m"}, std::pair{parameters_.beta_n, "beta_n"}})
    if (!(value > 0.0f && value <= 1.0f))
      throw InputError({}, std::string("hair ") + name + " must lie in (0, 1], got " + std::to_string(value));
  if (!(std::fabs(parameters_.alpha_deg) <= 45.0f))
    throw InputError({}, "hair alpha must lie in [-45, 45] degrees, got " + std::to_string(parameters_.alpha_deg));
}

HairMaterial::HairMaterial(SpectrumPtr sigma_a, HairParameters parameters)
    : HairMaterial(std::move(sigma_a), nullptr, parameters) {}

HairMaterial HairMaterial::from_reflectance(SpectrumPtr reflectance, HairParameters parameters) {
  if (!reflectance) throw InputError({}, "a hair material by reflectance needs a reflectance");
  return HairMaterial(nullptr, std::move(reflectance), parameters);
}

Bsdf HairMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  // The integrator shades a transmissive BSDF in Frame::from_normal(shading normal), unflipped (bsdf.h): the same
  // frame here gives the fibre's direction in the coordinates eval() and sample() will receive.
  const Vec2 fibre = hair_fibre_direction(Frame::from_normal(context.shading_normal), context.dpdu);
  const SampledSpectrum sigma_a =
      sigma_a_ ? max(sigma_a_->sample(lambda), Float4(0.0f))
               : HairBsdf::sigma_a_from_reflectance(reflectance_->sample(lambda), parameters_.beta_n);
  return HairBsdf(fibre, 2.0f * context.uv.y - 1.0f, sigma_a, parameters_);
}

Bsdf DiffuseTransmissionMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const Float4 r = clamp_unit(reflectance_->evaluate_at(context, lambda) * Float4(scale_));
  const Float4 t = clamp_unit(transmittance_->evaluate_at(context, lambda) * Float4(scale_));
  // More than all the incident flux scattered would create energy: keep R : T, scatter exactly everything.
  const Float4 total = r + t;
  const Float4 normalise = select(total > Float4(1.0f), Float4(1.0f) / total, Float4(1.0f));
  return DiffuseTransmissionBsdf(r * normalise, t * normalise);
}

ThinDielectricMaterial::ThinDielectricMaterial(SpectrumPtr ior, SpectrumPtr internal_transmittance)
    : ior_(std::move(ior)), internal_transmittance_(std::move(internal_transmittance)) {
  if (!ior_) throw InputError({}, "a thin dielectric needs an index of refraction");
  if (!(min_over_range(*ior_) > 0.0))
    throw InputError({}, "the index of refraction of " + ior_->describe() + " must be positive over 360-830 nm");
}

Bsdf ThinDielectricMaterial::bsdf(const MaterialContext&, const SampledWavelengths& lambda) const {
  if (internal_transmittance_) return ThinDielectricBsdf(ior_->sample(lambda), internal_transmittance_->sample(lambda));
  return ThinDielectricBsdf(ior_->sample(lambda));
}

namespace {

void check_layer(const CoatLayer& layer) {
  check_roughness(layer.roughness, "coat roughness");
  if (!(layer.thickness >= 0.0f && std::isfinite(layer.thickness)))
    throw InputError({}, "coat thickness must be a finite number ≥ 0, got " + std::to_string(layer.thickness));
  if (!(std::fabs(layer.g) < 1.0f)) throw InputError({}, "coat g must lie in (-1, 1), got " + std::to_string(layer.g));
  if (layer.walk.max_depth < 1 || layer.walk.samples < 1)
    throw InputError({}, "coat max_depth and samples must be at least 1");
}

}  // namespace

float CoatLayer::roughness_at(const MaterialContext& context) const {
  return roughness_texture ? clamp_roughness(roughness_texture->evaluate(context)) : roughness;
}

namespace {

/// The coat's index at the hero wavelength: the walk's interfaces have one index for all lanes.
float hero_coat_eta(const Spectrum& coat_ior, const SampledWavelengths& lambda) { return float(coat_ior.value(lambda.hero_nm())); }

LayerMedium layer_medium(const CoatLayer& layer, const MaterialContext& context, const SampledWavelengths& lambda) {
  const Float4 albedo = layer.albedo ? clamp_unit(layer.albedo->evaluate_at(context, lambda)) : Float4(0.0f);
  return {layer.thickness, albedo, layer.g};
}

TrowbridgeReitz coat_distribution(float roughness) { return distribution_for(roughness, roughness); }

void check_coat_ior(const Spectrum& coat_ior) {
  // η < 1 would make the coat's internal reflectance formula describe a coat less dense than air: not a coat.
  if (!(min_over_range(coat_ior) >= 1.0))
    throw InputError({}, "the coat index of " + coat_ior.describe() + " must be at least 1 over 360-830 nm");
}

}  // namespace

CoatedDiffuseMaterial::CoatedDiffuseMaterial(SpectralTexturePtr reflectance, SpectrumPtr coat_ior, CoatLayer layer)
    : reflectance_(std::move(reflectance)), coat_ior_(std::move(coat_ior)), layer_(std::move(layer)) {
  if (!reflectance_ || !coat_ior_) throw InputError({}, "a coated diffuse material needs a reflectance and a coat index");
  check_coat_ior(*coat_ior_);
  check_layer(layer_);
  // The closed form serves every hit where the coat is smooth: all of them, or with a textured roughness those
  // where it reads 0.
  if (!layer_.clear() || (!layer_.roughness_texture && layer_.roughness != 0.0f)) return;
  std::vector<double> lambda_nm, internal;
  for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 5.0) {
    lambda_nm.push_back(l);
    internal.push_back(coat_internal_reflectance(coat_ior_->value(l), layer_.thickness));
  }
  coat_internal_reflectance_ = std::make_shared<TabulatedSpectrum>(
      std::move(lambda_nm), std::move(internal), Extrapolation::clamp, "internal diffuse reflectance of the coat");
}

Bsdf CoatedDiffuseMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const Float4 base = clamp_unit(reflectance_->evaluate_at(context, lambda));
  const float roughness = layer_.roughness_at(context);
  if (roughness == 0.0f && coat_internal_reflectance_)
    return CoatedDiffuseBsdf::absorbing(base, coat_ior_->sample(lambda), coat_internal_reflectance_->sample(lambda),
                                        layer_.thickness);
  return LayeredBsdf(hero_coat_eta(*coat_ior_, lambda), coat_distribution(roughness), DiffuseBsdf(base),
                     layer_medium(layer_, context, lambda), layer_.walk);
}

CoatedConductorMaterial::CoatedConductorMaterial(SpectrumPtr coat_ior, ComplexIorSpectra conductor,
                                                 float conductor_roughness_u, float conductor_roughness_v, CoatLayer layer)
    : CoatedConductorMaterial(std::move(coat_ior), std::move(conductor), nullptr, conductor_roughness_u,
                              conductor_roughness_v, std::move(layer), false) {}

CoatedConductorMaterial::CoatedConductorMaterial(SpectrumPtr coat_ior, SpectralTexturePtr conductor_reflectance,
                                                 float conductor_roughness_u, float conductor_roughness_v, CoatLayer layer)
    : CoatedConductorMaterial(std::move(coat_ior), ComplexIorSpectra{}, std::move(conductor_reflectance),
                              conductor_roughness_u, conductor_roughness_v, std::move(layer), true) {}

CoatedConductorMaterial::CoatedConductorMaterial(SpectrumPtr coat_ior, ComplexIorSpectra conductor,
                                                 SpectralTexturePtr reflectance, float conductor_roughness_u,
                                                 float conductor_roughness_v, CoatLayer layer, bool by_reflectance)
    : coat_ior_(std::move(coat_ior)),
      conductor_(std::move(conductor)),
      reflectance_(std::move(reflectance)),
      conductor_distribution_(distribution_for(conductor_roughness_u, conductor_roughness_v)),
      layer_(std::move(layer)) {
  if (!coat_ior_) throw InputError({}, "a coated conductor needs a coat index");
  if (by_reflectance && !reflectance_) throw InputError({}, "a coated conductor by reflectance needs a reflectance");
  if (!by_reflectance && (!conductor_.n || !conductor_.k))
    throw InputError({}, "a coated conductor needs both n and k spectra");
  check_coat_ior(*coat_ior_);
  check_roughness(conductor_roughness_u, "conductor roughness");
  check_roughness(conductor_roughness_v, "conductor roughness");
  check_layer(layer_);
}

Bsdf CoatedConductorMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const float eta = hero_coat_eta(*coat_ior_, lambda);
  // The metal borders the coat, not air: its Fresnel factor uses the index relative to the coat.
  Float4 n, k;
  if (reflectance_) {
    const Float4 r = clamp(reflectance_->evaluate_at(context, lambda), Float4(0.0f), Float4(0.9999f));
    n = Float4(1.0f);
    k = Float4(2.0f) * sqrt(r / (Float4(1.0f) - r));
  } else {
    n = conductor_.n->sample(lambda);
    k = conductor_.k->sample(lambda);
  }
  const TrowbridgeReitz metal = conductor_roughness_u_ ? distribution_for(clamp_roughness(conductor_roughness_u_->evaluate(context)),
                                                                           clamp_roughness(conductor_roughness_v_->evaluate(context)))
                                                       : conductor_distribution_;
  const ConductorBsdf base(n / Float4(eta), k / Float4(eta), metal);
  return LayeredBsdf(eta, coat_distribution(layer_.roughness_at(context)), base, layer_medium(layer_, context, lambda),
                     layer_.walk);
}

CoatedConductorMaterial CoatedConductorMaterial::with_conductor_roughness(FloatTexturePtr roughness_u,
                                                                          FloatTexturePtr roughness_v) && {
  if (!roughness_u || !roughness_v) throw InputError({}, "a coated conductor needs both conductor roughness textures");
  conductor_roughness_u_ = std::move(roughness_u);
  conductor_roughness_v_ = std::move(roughness_v);
  return std::move(*this);
}

MeasuredMaterial::MeasuredMaterial(MeasuredBrdfPtr brdf) : brdf_(std::move(brdf)) {
  if (!brdf_) throw InputError({}, "a measured material needs its BRDF's tables");
}

Bsdf MeasuredMaterial::bsdf(const MaterialContext& /*context*/, const SampledWavelengths& lambda) const {
  return MeasuredBsdf(brdf_.get(), lambda.lambda_nm());
}

MixMaterial::MixMaterial(std::shared_ptr<const Material> first, std::shared_ptr<const Material> second,
                         FloatTexturePtr amount, uint32_t salt)
    : first_(std::move(first)), second_(std::move(second)), amount_(std::move(amount)), salt_(salt) {
  if (!first_ || !second_ || !amount_) throw InputError({}, "a mix material needs two materials and an amount");
}

const Material& MixMaterial::choose(const MaterialContext& context) const {
  const float amount = amount_->evaluate(context);
  // pbrt-v4 skips the hash where the choice is certain; so does this (and NaN amounts choose the first).
  if (!(amount > 0.0f)) return *first_;
  if (amount >= 1.0f) return *second_;
  const float u = unit_float_from_hash(hash32(context.hash() ^ salt_));
  return u < amount ? *second_ : *first_;
}

Bsdf MixMaterial::bsdf(const MaterialContext& context, const SampledWavelengths& lambda) const {
  return choose(context).bsdf(context, lambda);
}

bool MixMaterial::uses_tangents() const { return first_->uses_tangents() || second_->uses_tangents(); }

bool Material::uses_tangents() const {
  if (const auto* mix = std::get_if<MixMaterial>(&material_)) return mix->uses_tangents();
  // Hair reads ∂p/∂u as the fibre's direction (curves provide it; on other surfaces it is better than the fallback).
  return normal_modifier_ != nullptr || std::holds_alternative<HairMaterial>(material_);
}

Vec3 Material::shading_normal(const MaterialContext& context) const {
  if (const auto* mix = std::get_if<MixMaterial>(&material_)) return mix->choose(context).shading_normal(context);
  return normal_modifier_ ? normal_modifier_->shading_normal(context) : context.shading_normal;
}

}  // namespace rimu
