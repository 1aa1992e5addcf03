#include "transport/textures/float_texture.h"

#include "spectral/error.h"

namespace rimu {
void throw_missing_texture_input(const char* what) {
  throw InputError({}, std::string(what) + " needs all of its input textures");
}

Vec3 direction_mix_unit_direction(Vec3 direction) {
  const float len = length(direction);
  if (!(len > 0.0f) || !std::isfinite(len))
    throw InputError({}, "a direction mix texture needs a non-zero, finite direction");
  return direction / len;
}

ProductFloatTexture::ProductFloatTexture(FloatTexturePtr a, FloatTexturePtr b) : a_(std::move(a)), b_(std::move(b)) {
  require_texture_inputs("a product texture", a_, b_);
}

PowerFloatTexture::PowerFloatTexture(FloatTexturePtr a, float exponent) : a_(std::move(a)), exponent_(exponent) {
  require_texture_inputs("a power texture", a_);
}

MixFloatTexture::MixFloatTexture(FloatTexturePtr a, FloatTexturePtr b, FloatTexturePtr amount)
    : a_(std::move(a)), b_(std::move(b)), amount_(std::move(amount)) {
  require_texture_inputs("a mix texture", a_, b_, amount_);
}

float MixFloatTexture::evaluate(const MaterialContext& context) const {
  const float t = amount_->evaluate(context);
  // Only the inputs with a non-zero weight are looked up (an image lookup costs more than the test).
  const float a = t != 1.0f ? a_->evaluate(context) : 0.0f;
  const float b = t != 0.0f ? b_->evaluate(context) : 0.0f;
  return (1.0f - t) * a + t * b;
}

DirectionMixFloatTexture::DirectionMixFloatTexture(FloatTexturePtr a, FloatTexturePtr b, Vec3 direction)
    : a_(std::move(a)), b_(std::move(b)) {
  require_texture_inputs("a direction mix texture", a_, b_);
  direction_ = direction_mix_unit_direction(direction);
}

float DirectionMixFloatTexture::evaluate(const MaterialContext& context) const {
  const float w = direction_mix_weight(context, direction_);
  const float a = w != 0.0f ? a_->evaluate(context) : 0.0f;
  const float b = w != 1.0f ? b_->evaluate(context) : 0.0f;
  return w * a + (1.0f - w) * b;
}

CheckerboardFloatTexture::CheckerboardFloatTexture(FloatTexturePtr a, FloatTexturePtr b, TextureMapping mapping)
    : a_(std::move(a)), b_(std::move(b)), mapping_(mapping) {
  require_texture_inputs("a checkerboard texture", a_, b_);
}

}  // namespace rimu
