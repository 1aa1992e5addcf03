#include "transport/textures/spectral_texture_ops.h"

namespace rimu {

ProductSpectralTexture::ProductSpectralTexture(SpectralTexturePtr spectrum, FloatTexturePtr scale)
    : spectrum_(std::move(spectrum)), scale_(std::move(scale)) {
  require_texture_inputs("a product texture", spectrum_, scale_);
}

SampledSpectrum ProductSpectralTexture::evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const float k = scale_->evaluate(context);
  if (k == 0.0f) return SampledSpectrum(0.0f);
  return spectrum_->evaluate_at(context, lambda) * Float4(k);
}

SpectralTexturePair::SpectralTexturePair(SpectralTexturePtr a, SpectralTexturePtr b, const char* what)
    : a_(std::move(a)), b_(std::move(b)) {
  require_texture_inputs(what, a_, b_);
}

SampledSpectrum SpectralTexturePair::weighted_sum(const MaterialContext& context, const SampledWavelengths& lambda,
                                                  float weight_a, float weight_b) const {
  const SampledSpectrum a = weight_a != 0.0f ? a_->evaluate_at(context, lambda) : SampledSpectrum(0.0f);
  const SampledSpectrum b = weight_b != 0.0f ? b_->evaluate_at(context, lambda) : SampledSpectrum(0.0f);
  return a * Float4(weight_a) + b * Float4(weight_b);
}

MixSpectralTexture::MixSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, FloatTexturePtr amount)
    : SpectralTexturePair(std::move(a), std::move(b), "a mix texture"), amount_(std::move(amount)) {
  require_texture_inputs("a mix texture", amount_);
}

SampledSpectrum MixSpectralTexture::evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const float t = amount_->evaluate(context);
  return weighted_sum(context, lambda, 1.0f - t, t);  // 1 − t is 0 exactly when t is 1
}

DirectionMixSpectralTexture::DirectionMixSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, Vec3 direction)
    : SpectralTexturePair(std::move(a), std::move(b), "a direction mix texture"),
      direction_(direction_mix_unit_direction(direction)) {}

SampledSpectrum DirectionMixSpectralTexture::evaluate_at(const MaterialContext& context,
                                                         const SampledWavelengths& lambda) const {
  const float w = direction_mix_weight(context, direction_);
  return weighted_sum(context, lambda, w, 1.0f - w);
}

MappedSpectralTexture::MappedSpectralTexture(SpectralTexturePtr texture, TextureMapping mapping)
    : texture_(std::move(texture)), mapping_(mapping) {
  require_texture_inputs("a mapped texture", texture_);
}

CheckerboardSpectralTexture::CheckerboardSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b,
                                                         TextureMapping mapping)
    : SpectralTexturePair(std::move(a), std::move(b), "a checkerboard texture"), mapping_(mapping) {}

}  // namespace rimu
