#include "render/image/rgb_radiance_image.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rimu {

RgbRadianceImage::RgbRadianceImage(std::shared_ptr<const RgbImage> image,
                                         std::shared_ptr<const RgbUpsampler> upsampler)
    : width_(image->width()), height_(image->height()), image_(image), upsampler_(std::move(upsampler)) {
  // RgbImage::read has already rejected NaN/Inf pixels (naming the file and the pixel).
  luminance_.resize(size_t(width_) * size_t(height_));
  // Rows in parallel: every pixel is independent, so the result does not depend on the thread count.
  tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width_; ++x) {
        const Rgb rgb = image->pixel(x, y);
        const double y_value = upsampler_->space().to_xyz(rgb).y;
        luminance_[index(x, y)] = y_value > 0.0 ? float(y_value) : 0.0f;
      }
  });
}

SampledSpectrum RgbRadianceImage::radiance(int x, int y, const SampledWavelengths& lambda) const {
  return radiance_from(upsampler_->emission_coefficients(image_->pixel(x, y)), lambda);
}

SampledSpectrum RgbRadianceImage::radiance_from(const BasisCoefficients& coefficients,
                                                const SampledWavelengths& lambda) const {
  // S(λ) = emission_scale · max(0, s(λ)·Y) · W(λ), as EmissionSpectrum::evaluate with the shape clamped at 0
  // (basis truncation rings a few 1e-3 of the peak below zero where the exact shape is zero).
  const Float4 shape =
      upsampler_->basis().evaluate(coefficients, lambda.lambda_nm(), Float4(0.0f), Float4(INFINITY));
  return Float4(float(upsampler_->emission_scale())) * shape * upsampler_->illuminant()->sample(lambda);
}

double RgbRadianceImage::radiance_integral(int x, int y) const {
  const BasisCoefficients coefficients = upsampler_->emission_coefficients(image_->pixel(x, y));
  double spectral_sum = 0.0;  // the same sum, in the same order, as RadianceImage::radiance_integral
  for (const SampledWavelengths& lambda : radiance_integral_wavelengths())
    spectral_sum += sum(radiance_from(coefficients, lambda));
  return spectral_sum * radiance_integral_band_nm();
}

void RgbRadianceImage::radiance_integrals(int y, std::span<double> out) const {
  std::vector<BasisCoefficients> row(width_);
  for (int x = 0; x < width_; ++x) row[x] = upsampler_->emission_coefficients(image_->pixel(x, y));
  // Per pixel the same sum in the same order as radiance_integral (group by group), so the values are identical;
  // group by group, the thread's basis cache (UpsamplingBasis::at) refills 4 times per row instead of per pixel.
  std::fill(out.begin(), out.begin() + width_, 0.0);
  for (const SampledWavelengths& lambda : radiance_integral_wavelengths()) {
    const Float4 scale(float(upsampler_->emission_scale()));
    const SampledSpectrum white = upsampler_->illuminant()->sample(lambda);
    for (int x = 0; x < width_; ++x) {
      const Float4 shape = upsampler_->basis().evaluate(row[x], lambda.lambda_nm(), Float4(0.0f), Float4(INFINITY));
      out[x] += sum(scale * shape * white);  // radiance_from's products, in its order
    }
  }
  for (int x = 0; x < width_; ++x) out[x] *= radiance_integral_band_nm();
}

}  // namespace rimu
