// Image textures: RGB texels kept in the source's precision, filtered as RGB and upsampled once per lookup.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "render/image/mip_pyramid.h"
#include "render/image/rgb_image.h"
#include "render/image/rgb_texels.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "transport/textures/spectral_texture.h"

namespace rimu {

/// A reflectance texture from an image. The texels are kept in the source's precision (render/image/rgb_texels.h):
/// the file's 8-bit codes, 3 bytes per texel, for an 8-bit file; linear RGB floats, 12 bytes, otherwise. They are
/// MIP-mapped at load (render/image/mip_pyramid.h: a box-filtered pyramid, 8-bit levels averaged in linear light and
/// rounded to the nearest code; 4/3 of the image's texels in all: 4 bytes per image texel for an 8-bit file, 16 for
/// floats).
///
/// A lookup filters as `filter` says (evaluate_at, with the hit's footprint; evaluate(uv) is the bilinear lookup of
/// level 0): each texel it reads is decoded to linear RGB, scaled and inverted (below), and weighted; the weighted
/// RGB is upsampled once (RgbUpsampler::reflectance_coefficients: the smoothest spectrum, gamut-mapped into [0, 1],
/// 0.15-0.3 µs) and evaluated at the path's four wavelengths, clamped to [0, 1]. This is pbrt-v4's order (filter
/// the RGB, then upsample): the lookup's colour is the filtered colour of the texels, as when the texels' spectra
/// were blended (apart from colours the upsampler moves: beyond the brightness limit, the blend is mapped rather
/// than the texels); a blend of several colours gets the smoothest spectrum of the blended colour instead of the
/// blend of the texels' smoothest spectra (a metamer of it). docs/upsampling.md ("Fast path") has the error of the
/// upsampling added. A coarser level's texel is scaled and clamped as one texel (pbrt-v4 scales after filtering).
/// `scale` (≥ 0) and `invert` act on each texel's RGB as it is read, in pbrt-v4's order for a reflectance image:
/// v = scale·rgb, then max(0, 1 − v) if inverted, then clamped to [0, 1] per channel (a scale above 1 brightens
/// the texels up to white, as pbrt's does; a reflectance spectrum cannot exceed 1).
/// A reflectance texel's RGB after pbrt-v4's imagemap `scale` and `invert`: scale·rgb, then max(0, 1 − ·) if
/// inverted, clamped to [0, 1] per channel; unchanged (not clamped) for scale 1 without invert.
Rgb scaled_texel(Rgb rgb, float scale, bool invert);

class ImageTexture final : public SpectralTexture {
 public:
  /// Copies `image`'s texels (its bytes if it holds 8-bit codes) into the pyramid: the image may be freed after.
  ImageTexture(std::shared_ptr<const RgbImage> image, std::shared_ptr<const RgbUpsampler> upsampler, float scale,
               bool invert = false, TextureFilterOptions filter = {});
  SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const override;
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override {
    return evaluate_footprint(context.uv, context.duvdx, context.duvdy, lambda);
  }
  SampledSpectrum evaluate_footprint(Vec2 st, Vec2 dst_dx, Vec2 dst_dy, const SampledWavelengths& lambda) const override;

  int width() const { return bytes_ ? bytes_->width(0) : floats_->width(0); }
  int height() const { return bytes_ ? bytes_->height(0) : floats_->height(0); }
  int levels() const { return bytes_ ? bytes_->levels() : floats_->levels(); }
  /// Bytes of texels held over all levels.
  size_t texel_bytes() const {
    return bytes_ ? bytes_->texel_count() * sizeof(Rgb8Texel) : floats_->texel_count() * sizeof(LinearRgbTexel);
  }

 private:
  // The filtered, scaled linear RGB of a lookup (zero derivatives with `bilinear_only`: level 0's bilinear lookup).
  Rgb filtered_rgb(Vec2 st, Vec2 dst_dx, Vec2 dst_dy, bool bilinear_only) const;
  SampledSpectrum spectrum(Rgb rgb, const SampledWavelengths& lambda) const;

  std::optional<MipPyramid<Rgb8Texel>> bytes_;  // an 8-bit image's codes, decoded by codec_
  Rgb8Codec codec_;
  std::optional<MipPyramid<LinearRgbTexel>> floats_;  // any other image
  float scale_;
  bool invert_;
  TextureFilterOptions filter_;
  std::shared_ptr<const RgbUpsampler> upsampler_;
};

}  // namespace rimu
