#include "transport/spectral_texture_ops.h"

#include "spectral/error.h"

namespace rimu {
namespace {

template <typename T>
void require(const T& t, const char* what) {
  if (!t) throw InputError({}, std::string(what) + " needs all of its input textures");
}

}  // namespace

ProductSpectralTexture::ProductSpectralTexture(SpectralTexturePtr spectrum, FloatTexturePtr scale)
    : spectrum_(std::move(spectrum)), scale_(std::move(scale)) {
  require(spectrum_, "a product texture");
  require(scale_, "a product texture");
}

SampledSpectrum ProductSpectralTexture::evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const float k = scale_->evaluate(context);
  if (k == 0.0f) return SampledSpectrum(0.0f);
  return spectrum_->evaluate_at(context, lambda) * Float4(k);
}

MixSpectralTexture::MixSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, FloatTexturePtr amount)
    : a_(std::move(a)), b_(std::move(b)), amount_(std::move(amount)) {
  require(a_, "a mix texture");
  require(b_, "a mix texture");
  require(amount_, "a mix texture");
}

SampledSpectrum MixSpectralTexture::evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const float t = amount_->evaluate(context);
  const SampledSpectrum a = t != 1.0f ? a_->evaluate_at(context, lambda) : SampledSpectrum(0.0f);
  const SampledSpectrum b = t != 0.0f ? b_->evaluate_at(context, lambda) : SampledSpectrum(0.0f);
  return a * Float4(1.0f - t) + b * Float4(t);
}

DirectionMixSpectralTexture::DirectionMixSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, Vec3 direction)
    : a_(std::move(a)), b_(std::move(b)) {
  require(a_, "a direction mix texture");
  require(b_, "a direction mix texture");
  const float len = length(direction);
  if (!(len > 0.0f) || !std::isfinite(len))
    throw InputError({}, "a direction mix texture needs a non-zero, finite direction");
  direction_ = direction / len;
}

SampledSpectrum DirectionMixSpectralTexture::evaluate_at(const MaterialContext& context,
                                                         const SampledWavelengths& lambda) const {
  const float w = direction_mix_weight(context, direction_);
  const SampledSpectrum a = w != 0.0f ? a_->evaluate_at(context, lambda) : SampledSpectrum(0.0f);
  const SampledSpectrum b = w != 1.0f ? b_->evaluate_at(context, lambda) : SampledSpectrum(0.0f);
  return a * Float4(w) + b * Float4(1.0f - w);
}

CheckerboardSpectralTexture::CheckerboardSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, TextureMapping mapping)
    : a_(std::move(a)), b_(std::move(b)), mapping_(mapping) {
  require(a_, "a checkerboard texture");
  require(b_, "a checkerboard texture");
}

}  // namespace rimu
