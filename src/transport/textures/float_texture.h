// A scalar that varies over a surface: roughness, a mix amount; and the combinators pbrt-v4's scenes build from them.
#pragma once

#include <cmath>
#include <memory>

#include "transport/textures/material_context.h"
#include "transport/textures/texture_mapping.h"

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

/// Whether ⌊x⌋ is odd (by fmod, so that no float, however large or NaN, overflows an integer conversion).
inline bool checkerboard_odd_cell(float x) { return std::fmod(std::floor(x), 2.0f) != 0.0f; }

/// Which of a 2D checkerboard's two textures covers (s, t): the first where ⌊s⌋ + ⌊t⌋ is even (pbrt-v4's
/// checkerboard, point-sampled: the footprint is not used to box-filter it).
inline bool checkerboard_first(Vec2 st) { return checkerboard_odd_cell(st.x) == checkerboard_odd_cell(st.y); }

/// The same for any mapping: a `solid` mapping gives pbrt-v4's 3D checkerboard (the first texture where
/// ⌊x⌋ + ⌊y⌋ + ⌊z⌋ of the texture-space point is even: unit cubes).
inline bool checkerboard_first(const TextureMapping& mapping, const MaterialContext& context) {
  if (mapping.kind != TextureMapping::Kind::solid) return checkerboard_first(mapping.st(context));
  const Vec3 p = mapping.point(context);
  return (checkerboard_odd_cell(p.x) != checkerboard_odd_cell(p.y)) == checkerboard_odd_cell(p.z);
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

/// a on the even squares of the mapped grid (cubes for a solid mapping), b on the odd ones (pbrt-v4's
/// "checkerboard", 2D or 3D).
class CheckerboardFloatTexture final : public FloatTexture {
 public:
  CheckerboardFloatTexture(FloatTexturePtr a, FloatTexturePtr b, TextureMapping mapping);
  float evaluate(const MaterialContext& context) const override {
    return checkerboard_first(mapping_, context) ? a_->evaluate(context) : b_->evaluate(context);
  }

 private:
  FloatTexturePtr a_, b_;
  TextureMapping mapping_;
};

}  // namespace rimu
