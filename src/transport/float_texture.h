// A scalar that varies over a surface: roughness, a mix amount; and the combinators pbrt-v4's scenes build from them.
#pragma once

#include <cmath>
#include <memory>

#include "transport/material_context.h"

namespace rimu {

/// A number per surface point. Implementations are immutable after construction and safe to call from many
/// threads; evaluate() is on the per-hit path (no allocation).
class FloatTexture {
 public:
  virtual ~FloatTexture() = default;
  virtual float evaluate(const MaterialContext& context) const = 0;
};

using FloatTexturePtr = std::shared_ptr<const FloatTexture>;

/// The same number everywhere.
class ConstantFloatTexture final : public FloatTexture {
 public:
  explicit ConstantFloatTexture(float value) : value_(value) {}
  float evaluate(const MaterialContext&) const override { return value_; }
  float value() const { return value_; }

 private:
  float value_;
};

/// pbrt-v4's 2D "uv" texture mapping: (s, t) = (su·u + du, sv·v + dv).
struct UvMapping {
  float su = 1, sv = 1, du = 0, dv = 0;
  Vec2 operator()(Vec2 uv) const { return {su * uv.x + du, sv * uv.y + dv}; }
};

/// Which of a 2D checkerboard's two textures covers (s, t): the first where ⌊s⌋ + ⌊t⌋ is even (pbrt-v4's
/// checkerboard, point-sampled: Rimu has no ray differentials to box-filter it with).
inline bool checkerboard_first(Vec2 st) {
  return (static_cast<long long>(std::floor(st.x)) + static_cast<long long>(std::floor(st.y))) % 2 == 0;
}

/// The weight of the first texture of pbrt-v4's "directionmix": |n·direction|, n the geometric normal.
inline float direction_mix_weight(const MaterialContext& context, Vec3 unit_direction) {
  return std::fmin(1.0f, std::fabs(dot(context.geometric_normal, unit_direction)));
}

/// Throws InputError ("<what> needs all of its input textures") unless every input is set: the check every
/// combinator's constructor makes, float or spectral.
[[noreturn]] void throw_missing_texture_input(const char* what);
template <typename... Inputs>
void require_texture_inputs(const char* what, const Inputs&... inputs) {
  if (!(static_cast<bool>(inputs) && ...)) throw_missing_texture_input(what);
}

/// `direction` normalised for direction_mix_weight(); throws InputError if it is zero or not finite.
Vec3 direction_mix_unit_direction(Vec3 direction);

/// a·b (pbrt-v4's "scale": tex·scale).
class ProductFloatTexture final : public FloatTexture {
 public:
  ProductFloatTexture(FloatTexturePtr a, FloatTexturePtr b);
  float evaluate(const MaterialContext& context) const override { return a_->evaluate(context) * b_->evaluate(context); }

 private:
  FloatTexturePtr a_, b_;
};

/// a^exponent, 0 where a ≤ 0 or NaN (maps pbrt-v4's roughness textures onto Rimu's perceptual roughness).
class PowerFloatTexture final : public FloatTexture {
 public:
  PowerFloatTexture(FloatTexturePtr a, float exponent);
  float evaluate(const MaterialContext& context) const override {
    const float a = a_->evaluate(context);
    return a > 0.0f ? std::pow(a, exponent_) : 0.0f;
  }

 private:
  FloatTexturePtr a_;
  float exponent_;
};

/// (1 − t)·a + t·b with t = amount (pbrt-v4's "mix"; t is not clamped, as in pbrt).
class MixFloatTexture final : public FloatTexture {
 public:
  MixFloatTexture(FloatTexturePtr a, FloatTexturePtr b, FloatTexturePtr amount);
  float evaluate(const MaterialContext& context) const override;

 private:
  FloatTexturePtr a_, b_, amount_;
};

/// w·a + (1 − w)·b with w = |n·direction| (pbrt-v4's "directionmix"): a faces the direction, b is side-on.
class DirectionMixFloatTexture final : public FloatTexture {
 public:
  /// Throws InputError if `direction` is zero or not finite (it is normalised here).
  DirectionMixFloatTexture(FloatTexturePtr a, FloatTexturePtr b, Vec3 direction);
  float evaluate(const MaterialContext& context) const override;

 private:
  FloatTexturePtr a_, b_;
  Vec3 direction_;
};

/// a on the even squares of the mapped uv grid, b on the odd ones (pbrt-v4's 2D "checkerboard").
class CheckerboardFloatTexture final : public FloatTexture {
 public:
  CheckerboardFloatTexture(FloatTexturePtr a, FloatTexturePtr b, UvMapping mapping);
  float evaluate(const MaterialContext& context) const override {
    return checkerboard_first(mapping_(context.uv)) ? a_->evaluate(context) : b_->evaluate(context);
  }

 private:
  FloatTexturePtr a_, b_;
  UvMapping mapping_;
};

}  // namespace rimu
