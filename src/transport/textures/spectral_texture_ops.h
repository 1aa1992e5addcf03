// Spectral textures built from others (pbrt-v4's "scale", "mix", "directionmix", "checkerboard" spectrum textures).
#pragma once

#include "transport/textures/float_texture.h"
#include "transport/textures/spectral_texture.h"

namespace rimu {

/// A spectral texture defined at surface points: evaluate(uv) asks at a point known only by its uv (normal, wo and
/// position zero), which is what a lookup without a hit means.
class SpectralTextureAtPoint : public SpectralTexture {
 public:
  SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const final {
    return evaluate_at(MaterialContext::at_uv(uv), lambda);
  }
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override = 0;
};

/// spectrum·scale (pbrt-v4's "scale").
class ProductSpectralTexture final : public SpectralTextureAtPoint {
 public:
  ProductSpectralTexture(SpectralTexturePtr spectrum, FloatTexturePtr scale);
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override;

 private:
  SpectralTexturePtr spectrum_;
  FloatTexturePtr scale_;
};

/// The base of the combinators of two spectral textures a and b: the inputs, and their weighted sum.
class SpectralTexturePair : public SpectralTextureAtPoint {
 protected:
  /// Throws InputError naming `what` if an input is missing.
  SpectralTexturePair(SpectralTexturePtr a, SpectralTexturePtr b, const char* what);
  /// weight_a·a + weight_b·b; an input whose weight is 0 is not looked up (an image lookup costs more than the test).
  SampledSpectrum weighted_sum(const MaterialContext& context, const SampledWavelengths& lambda, float weight_a,
                               float weight_b) const;

  SpectralTexturePtr a_, b_;
};

/// (1 − t)·a + t·b, t = amount (pbrt-v4's "mix").
class MixSpectralTexture final : public SpectralTexturePair {
 public:
  MixSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, FloatTexturePtr amount);
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override;

 private:
  FloatTexturePtr amount_;
};

/// w·a + (1 − w)·b, w = |n·direction| (pbrt-v4's "directionmix").
class DirectionMixSpectralTexture final : public SpectralTexturePair {
 public:
  /// Throws InputError if `direction` is zero or not finite.
  DirectionMixSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, Vec3 direction);
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override;

 private:
  Vec3 direction_;
};

/// A texture looked up by uv (an image) read at the (s, t) of a mapping instead of the surface's own uv: pbrt-v4's
/// imagemap with "mapping", "uscale", "vscale", "udelta", "vdelta".
class MappedSpectralTexture final : public SpectralTextureAtPoint {
 public:
  MappedSpectralTexture(SpectralTexturePtr texture, TextureMapping mapping);
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override {
    const TextureFootprint f = mapping_.image_footprint(context);
    return texture_->evaluate_footprint(f.st, f.dst_dx, f.dst_dy, lambda);
  }

 private:
  SpectralTexturePtr texture_;
  TextureMapping mapping_;
};

/// a on the even squares (cubes for a solid mapping), b on the odd ones (pbrt-v4's "checkerboard", point-sampled).
class CheckerboardSpectralTexture final : public SpectralTexturePair {
 public:
  CheckerboardSpectralTexture(SpectralTexturePtr a, SpectralTexturePtr b, TextureMapping mapping);
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override {
    return checkerboard_first(mapping_, context) ? a_->evaluate_at(context, lambda) : b_->evaluate_at(context, lambda);
  }

 private:
  TextureMapping mapping_;
};

}  // namespace rimu
