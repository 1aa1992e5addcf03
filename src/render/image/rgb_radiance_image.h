// An RGB image (an environment map, an emission image) converted once to spectral radiance per pixel.
#pragma once

#include <memory>
#include <vector>

#include "render/image/rgb_image.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "transport/lights/radiance_image.h"

namespace rimu {

/// Pixel RGB is read as luminance-scaled colour: RGB with Y = 1 means 1 cd/m² (RgbUpsampler::upsample_emission's
/// convention), turned into W/(m²·sr·nm) shaped like the colour space's white. A pixel is upsampled when it is
/// looked up (RgbUpsampler::emission_coefficients, then a 16-term dot product per lane times the white's table), from
/// the image as read (its file's precision: 3 bytes for an 8-bit file, 12 for a float one) and a luminance per pixel.
/// Until 6 December 2026 every pixel's 64 bytes of basis coefficients were computed at construction: a 2048² sky
/// took 402 MiB at the peak instead of 189, for no measurable speed (docs/benchmarks.md, "pbrt-v3 scenes"). The
/// coefficients are the same either way, so images are bit-identical.
class RgbRadianceImage final : public RadianceImage {
 public:
  RgbRadianceImage(std::shared_ptr<const RgbImage> image, std::shared_ptr<const RgbUpsampler> upsampler);
  int width() const override { return width_; }
  int height() const override { return height_; }
  SampledSpectrum radiance(int x, int y, const SampledWavelengths& lambda) const override;
  float luminance(int x, int y) const override { return luminance_[index(x, y)]; }
  /// The pixel upsampled once for the 16 wavelengths (radiance() would upsample it per lane group).
  double radiance_integral(int x, int y) const override;
  /// The row's pixels upsampled once each, then evaluated one wavelength group at a time (same values).
  void radiance_integrals(int y, std::span<double> out) const override;

 private:
  size_t index(int x, int y) const { return size_t(y) * size_t(width_) + size_t(x); }
  SampledSpectrum radiance_from(const BasisCoefficients& coefficients, const SampledWavelengths& lambda) const;

  int width_ = 0, height_ = 0;
  std::shared_ptr<const RgbImage> image_;  // the pixels as read
  std::vector<float> luminance_;           // Y ≥ 0 (0 where Y ≤ 0), for importance sampling
  std::shared_ptr<const RgbUpsampler> upsampler_;
};

}  // namespace rimu
