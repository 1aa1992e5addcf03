// Image textures: RGB pixels converted once, at load time, to upsampled reflectance spectra per texel.
#pragma once

#include <memory>
#include <vector>

#include "render/image/mip_pyramid.h"
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
///
/// Filtering: the coefficients are MIP-mapped at load (render/image/mip_pyramid.h: a box-filtered pyramid of the
/// coefficients, which averages the spectra and so their colours exactly; 64 bytes per texel of each level, 4/3 of
/// the image's in all: 85 bytes per image texel). A material's lookup (evaluate_at, with the hit's footprint)
/// filters as `filter` says, blending every texel's coefficients with its weight before one evaluation at the four
/// wavelengths, clamped once; evaluate(uv) is the unfiltered bilinear lookup of level 0.
/// A reflectance texel's RGB after pbrt-v4's imagemap `scale` and `invert`: scale·rgb, then max(0, 1 − ·) if
/// inverted, clamped to [0, 1] per channel; unchanged (not clamped) for scale 1 without invert.
Rgb scaled_texel(Rgb rgb, float scale, bool invert);

class ImageTexture final : public SpectralTexture {
 public:
  ImageTexture(std::shared_ptr<const RgbImage> image, std::shared_ptr<const RgbUpsampler> upsampler, float scale,
               bool invert = false, TextureFilterOptions filter = {});
  SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const override;
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override {
    return evaluate_footprint(context.uv, context.duvdx, context.duvdy, lambda);
  }
  SampledSpectrum evaluate_footprint(Vec2 st, Vec2 dst_dx, Vec2 dst_dy, const SampledWavelengths& lambda) const override;

  int width() const { return pyramid_.width(0); }
  int height() const { return pyramid_.height(0); }
  /// Texel (x, y)'s coefficients (row 0 at the top, as RgbImage).
  const BasisCoefficients& texel(int x, int y) const { return pyramid_.texel(0, x, y); }
  const MipPyramid<BasisCoefficients>& pyramid() const { return pyramid_; }

 private:
  MipPyramid<BasisCoefficients> pyramid_;
  TextureFilterOptions filter_;
  std::shared_ptr<const RgbUpsampler> upsampler_;  // owns the basis the coefficients refer to
};

}  // namespace rimu
