// Image textures: RGB pixels converted once, at load time, to upsampled reflectance spectra per texel.
#pragma once

#include <memory>
#include <vector>

#include "render/image/rgb_image.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "transport/textures/spectral_texture.h"

namespace rimu {

/// A reflectance texture from an image. Construction upsamples every texel once (RgbUpsampler::
/// reflectance_coefficients: the smoothest spectrum, gamut-mapped into [0, 1], as 16 basis coefficients, 0.15-0.3 µs
/// per texel, 64 bytes per texel). A lookup blends the four texels around (u, v) bilinearly — blending the
/// spectra, so the result's colour is the bilinear blend of the texels' colours — and evaluates the blend at the
/// path's four wavelengths (UpsamplingBasis::evaluate: one 16-term dot product per lane), clamped to [0, 1]: a
/// fetch, a blend, a dot product, no solve. docs/upsampling.md ("Fast path") has the error added.
/// `scale` (≥ 0) and `invert` act on each texel's RGB before it is upsampled, in pbrt-v4's order for a reflectance
/// image: v = scale·rgb, then max(0, 1 − v) if inverted, then clamped to [0, 1] per channel (a scale above 1
/// brightens the texels up to white, as pbrt's does; a reflectance spectrum cannot exceed 1).
/// A reflectance texel's RGB after pbrt-v4's imagemap `scale` and `invert`: scale·rgb, then max(0, 1 − ·) if
/// inverted, clamped to [0, 1] per channel; unchanged (not clamped) for scale 1 without invert.
Rgb scaled_texel(Rgb rgb, float scale, bool invert);

class ImageTexture final : public SpectralTexture {
 public:
  ImageTexture(std::shared_ptr<const RgbImage> image, std::shared_ptr<const RgbUpsampler> upsampler, float scale,
               bool invert = false);
  SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const override;

  int width() const { return width_; }
  int height() const { return height_; }
  /// Texel (x, y)'s coefficients (row 0 at the top, as RgbImage).
  const BasisCoefficients& texel(int x, int y) const { return texels_[size_t(y) * size_t(width_) + size_t(x)]; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<BasisCoefficients> texels_;
  std::shared_ptr<const RgbUpsampler> upsampler_;  // owns the basis the coefficients refer to
};

}  // namespace rimu
