#include "render/image/image_texture.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rimu {

Rgb scaled_texel(Rgb rgb, float scale, bool invert) {
  const auto one = [&](double v) {
    v *= double(scale);
    if (invert) v = std::max(0.0, 1.0 - v);
    return std::clamp(v, 0.0, 1.0);
  };
  return (scale == 1.0f && !invert) ? rgb : Rgb{one(rgb.r), one(rgb.g), one(rgb.b)};
}

ImageTexture::ImageTexture(std::shared_ptr<const RgbImage> image, std::shared_ptr<const RgbUpsampler> upsampler,
                           float scale, bool invert, TextureFilterOptions filter)
    : scale_(scale), invert_(invert), filter_(filter), upsampler_(std::move(upsampler)) {
  const int width = image->width(), height = image->height();
  const size_t count = size_t(width) * size_t(height);
  if (image->is_8bit()) {
    codec_.table = image->decode_table();
    std::vector<Rgb8Texel> texels(count);
    const std::vector<std::uint8_t>& bytes = image->bytes();
    for (size_t i = 0; i < count; ++i) texels[i].code = {bytes[3 * i], bytes[3 * i + 1], bytes[3 * i + 2]};
    bytes_.emplace(width, height, std::move(texels), codec_);
  } else {
    // RgbImage::read has already rejected NaN/Inf pixels (naming the file and the pixel).
    std::vector<LinearRgbTexel> texels(count);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const Rgb p = image->pixel(x, y);
        texels[size_t(y) * size_t(width) + size_t(x)] = {float(p.r), float(p.g), float(p.b)};
      }
    floats_.emplace(width, height, std::move(texels));
  }
}

Rgb ImageTexture::filtered_rgb(Vec2 st, Vec2 dst_dx, Vec2 dst_dy, bool bilinear_only) const {
  const TextureFilterOptions& options = bilinear_only ? TextureFilterOptions{TextureFilter::bilinear} : filter_;
  Rgb sum;
  const auto add = [&](LinearRgbTexel t, float w) {
    const Rgb rgb = scaled_texel(Rgb{t.r, t.g, t.b}, scale_, invert_);
    sum.r += double(w) * rgb.r, sum.g += double(w) * rgb.g, sum.b += double(w) * rgb.b;
  };
  if (bytes_) {
    bytes_->lookup(options, st, dst_dx, dst_dy, [&](const Rgb8Texel* const t[4], const float w[4]) {
      for (int j = 0; j < 4; ++j)
        if (w[j] != 0.0f) add(codec_.decode(*t[j]), w[j]);
    });
  } else {
    floats_->lookup(options, st, dst_dx, dst_dy, [&](const LinearRgbTexel* const t[4], const float w[4]) {
      for (int j = 0; j < 4; ++j)
        if (w[j] != 0.0f) add(*t[j], w[j]);
    });
  }
  return sum;
}

SampledSpectrum ImageTexture::spectrum(Rgb rgb, const SampledWavelengths& lambda) const {
  // Every texel's scaled RGB is finite, so the upsampler cannot throw. Clamped: the basis truncation rings a few
  // 1e-3 around the exact spectrum's zeros and peaks.
  const BasisCoefficients c = upsampler_->reflectance_coefficients(rgb);
  return upsampler_->basis().evaluate(c, lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
}

SampledSpectrum ImageTexture::evaluate(Vec2 uv, const SampledWavelengths& lambda) const {
  // Texel centres at (i + 0.5)/width, v = 0 at the bottom row, repeat (RgbImage::bilinear's footprint).
  return spectrum(filtered_rgb(uv, {}, {}, true), lambda);
}

SampledSpectrum ImageTexture::evaluate_footprint(Vec2 st, Vec2 dst_dx, Vec2 dst_dy,
                                                 const SampledWavelengths& lambda) const {
  return spectrum(filtered_rgb(st, dst_dx, dst_dy, false), lambda);
}

}  // namespace rimu
