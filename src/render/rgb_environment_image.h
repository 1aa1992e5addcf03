// An equirectangular environment image read through OpenImageIO, upsampled to spectral radiance per lookup.
#pragma once

#include <memory>

#include "render/rgb_image.h"
#include "spectral/rgb_upsampler.h"
#include "transport/environment_image.h"

namespace rimu {

/// Pixel RGB is read as luminance-scaled colour: RGB with Y = 1 means 1 cd/m² (RgbUpsampler::upsample_emission's
/// convention), turned into W/(m²·sr·nm) shaped like the colour space's white. Upsampling happens per lookup (a few
/// µs; once or twice per path), so the image costs 12 bytes per pixel instead of a spectrum per pixel.
class RgbEnvironmentImage final : public EnvironmentImage {
 public:
  RgbEnvironmentImage(std::shared_ptr<const RgbImage> image, std::shared_ptr<const RgbUpsampler> upsampler)
      : image_(std::move(image)), upsampler_(std::move(upsampler)) {}
  int width() const override { return image_->width(); }
  int height() const override { return image_->height(); }
  SampledSpectrum radiance(int x, int y, const SampledWavelengths& lambda) const override {
    return upsampler_->upsample_emission(image_->pixel(x, y)).spectrum.evaluate(lambda);
  }
  float luminance(int x, int y) const override {
    const double y_value = upsampler_->space().to_xyz(image_->pixel(x, y)).y;
    return y_value > 0.0 ? float(y_value) : 0.0f;
  }

 private:
  std::shared_ptr<const RgbImage> image_;
  std::shared_ptr<const RgbUpsampler> upsampler_;
};

}  // namespace rimu
