// A float texture from an image's first channel (pbrt-v4's float "imagemap"): roughness maps, mix amounts.
#pragma once

#include <cmath>
#include <memory>

#include "render/image/alpha_mask.h"
#include "transport/textures/float_texture.h"
#include "transport/textures/texture_mapping.h"

namespace rimu {

/// pbrt-v4's FloatImageTexture: v = scale·value(uv), then max(0, 1 − v) if `invert` (in that order, after filtering,
/// as pbrt does). The values are read once at load (AlphaMask::read: one channel, sRGB-decoded if asked, not
/// clamped: an EXR map keeps values beyond [0, 1] as pbrt does) and looked up bilinearly, coordinates repeating, v = 0 the bottom row. Cost per lookup: four loads
/// and two flops, no decoding.
class ImageFloatTexture final : public FloatTexture {
 public:
  /// `values` must have been read without inversion (it is applied here, after the scale); the image is read at
  /// the (s, t) of `mapping` (default: the surface's own uv).
  ImageFloatTexture(std::shared_ptr<const AlphaMask> values, float scale, bool invert, TextureMapping mapping = {})
      : values_(std::move(values)), scale_(scale), invert_(invert), mapping_(mapping) {}
  float evaluate(const MaterialContext& context) const override {
    const float v = scale_ * values_->evaluate(mapping_.image_st(context));
    return invert_ ? std::fmax(0.0f, 1.0f - v) : v;
  }

 private:
  std::shared_ptr<const AlphaMask> values_;
  float scale_;
  bool invert_;
  TextureMapping mapping_;
};

}  // namespace rimu
