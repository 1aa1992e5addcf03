#include "render/image/image_texture.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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
    : filter_(filter), upsampler_(std::move(upsampler)) {
  const int width = image->width(), height = image->height();
  // RgbImage::read has already rejected NaN/Inf pixels (naming the file and the pixel), so this cannot throw.
  // Rows in parallel: every texel is independent, so the result does not depend on the thread count.
  std::vector<BasisCoefficients> texels(size_t(width) * size_t(height));
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width; ++x)
        texels[size_t(y) * size_t(width) + size_t(x)] =
            upsampler_->reflectance_coefficients(scaled_texel(image->pixel(x, y), scale, invert));
  });
  pyramid_ = MipPyramid<BasisCoefficients>(width, height, std::move(texels));
}

SampledSpectrum ImageTexture::evaluate(Vec2 uv, const SampledWavelengths& lambda) const {
  // The footprint of RgbImage::bilinear: texel centres at (i + 0.5)/width, v = 0 at the bottom row, repeat.
  const int width_ = width(), height_ = height();
  const float x = (uv.x - std::floor(uv.x)) * float(width_) - 0.5f;
  const float y = (1.0f - (uv.y - std::floor(uv.y))) * float(height_) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  auto wrap = [](int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); };
  const int x0 = wrap(int(fx), width_), x1 = wrap(int(fx) + 1, width_);
  const int y0 = wrap(int(fy), height_), y1 = wrap(int(fy) + 1, height_);
  const BasisCoefficients* t[4] = {&texel(x0, y0), &texel(x1, y0), &texel(x0, y1), &texel(x1, y1)};
  const float w[4] = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
  // Clamped: the basis truncation rings a few 1e-3 around the exact spectrum's zeros and peaks.
  return upsampler_->basis().evaluate_blend(t, w, lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
}

SampledSpectrum ImageTexture::evaluate_footprint(Vec2 st, Vec2 dst_dx, Vec2 dst_dy,
                                                 const SampledWavelengths& lambda) const {
  // Unclamped blends summed, then one clamp: the filtered spectrum is the weighted mean of the texels' (linear in
  // the coefficients), clamped as a single texel's is.
  const UpsamplingBasis& basis = upsampler_->basis();
  const Float4 unbounded(std::numeric_limits<float>::infinity());
  Float4 sum(0.0f);
  pyramid_.lookup(filter_, st, dst_dx, dst_dy, [&](const BasisCoefficients* const t[4], const float w[4]) {
    sum = sum + basis.evaluate_blend(t, w, lambda.lambda_nm(), -unbounded, unbounded);
  });
  return clamp(sum, Float4(0.0f), Float4(1.0f));
}

}  // namespace rimu
