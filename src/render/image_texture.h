// Image textures: RGB pixels upsampled to a reflectance spectrum at every lookup.
#pragma once

#include <memory>

#include "render/rgb_image.h"
#include "spectral/rgb_upsampler.h"
#include "transport/spectral_texture.h"

namespace rimu {

/// A reflectance texture from an image: bilinear RGB at (u, v), then upsampled (RgbUpsampler::upsample_reflectance,
/// gamut-mapped into [0, 1]) and evaluated at the path's four wavelengths. Upsampling per lookup keeps memory at
/// 12 bytes per texel and makes filtering happen in RGB, where the artist painted; it costs ~2.4 µs per lookup
/// (RgbUpsampler::reflectance_spectrum, which skips upsample_reflectance's diagnostics: ~3.3 µs with them; most of
/// the rest is the exact colour correction, docs/upsampling.md). NaN/Inf texels are rejected when the image is read, so lookups cannot fail.
class ImageTexture final : public SpectralTexture {
 public:
  ImageTexture(std::shared_ptr<const RgbImage> image, std::shared_ptr<const RgbUpsampler> upsampler, float scale)
      : image_(std::move(image)), upsampler_(std::move(upsampler)), scale_(scale) {}
  SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const override;

 private:
  std::shared_ptr<const RgbImage> image_;
  std::shared_ptr<const RgbUpsampler> upsampler_;
  float scale_;
};

}  // namespace rimu
