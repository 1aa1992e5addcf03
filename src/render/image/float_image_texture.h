// A float texture from an image's first channel (pbrt-v4's float "imagemap"): roughness maps, mix amounts.
#pragma once

#include <cmath>
#include <memory>

#include "render/image/alpha_mask.h"
#include "render/image/mip_pyramid.h"
#include "transport/textures/float_texture.h"
#include "transport/textures/texture_mapping.h"

namespace rimu {

/// pbrt-v4's FloatImageTexture: v = scale·value(uv), then max(0, 1 − v) if `invert` (in that order, after filtering,
/// as pbrt does). The values are read once at load (AlphaMask::read: one channel, sRGB-decoded if asked, not
/// clamped: an EXR map keeps values beyond [0, 1] as pbrt does), MIP-mapped (render/image/mip_pyramid.h: 4 bytes
/// per texel, 4/3 of that over the levels) and looked up by `filter` over the hit's footprint, coordinates
/// repeating, v = 0 the bottom row. Cost per bilinear lookup: four loads and a few flops, no decoding.
class ImageFloatTexture final : public FloatTexture {
 public:
  /// `values` must have been read without inversion (it is applied here, after the scale); the image is read at
  /// the (s, t) of `mapping` (default: the surface's own uv).
  ImageFloatTexture(const std::shared_ptr<const AlphaMask>& values, float scale, bool invert, TextureMapping mapping = {},
                    TextureFilterOptions filter = {})
      : pyramid_(values->width(), values->height(), values->texels()), filter_(filter), scale_(scale), invert_(invert),
        mapping_(mapping) {}
  float evaluate(const MaterialContext& context) const override {
    const TextureFootprint f = mapping_.image_footprint(context);
    float value = 0.0f;
    pyramid_.lookup(filter_, f.st, f.dst_dx, f.dst_dy, [&](const float* const t[4], const float w[4]) {
      value += w[0] * *t[0] + w[1] * *t[1] + w[2] * *t[2] + w[3] * *t[3];
    });
    const float v = scale_ * value;
    return invert_ ? std::fmax(0.0f, 1.0f - v) : v;
  }

 private:
  MipPyramid<float> pyramid_;
  TextureFilterOptions filter_;
  float scale_;
  bool invert_;
  TextureMapping mapping_;
};

}  // namespace rimu
