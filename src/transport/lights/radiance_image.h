// An image of spectral radiance, pixel by pixel: what an environment light (environment_light.h) and an area light
// with an emission image (textured_emission.h) read.
//
// An interface so that the render side can supply image files' pixels upsampled to spectra (or, in RGB transport,
// as RGB) while transport stays free of image libraries. Pixel (x, y): column x in [0, width), row y in
// [0, height), row 0 at the TOP of the image. Where each pixel is (a direction, a point of a surface) is the
// light's business.
#pragma once

#include <array>
#include <span>

#include "spectral/wavelengths/sampled_wavelengths.h"

namespace rimu {

class RadianceImage {
 public:
  virtual ~RadianceImage() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  /// Spectral radiance of pixel (x, y) at the four wavelengths, W/(m²·sr·nm) before the light's scale.
  /// Called per sample: it must be cheap and thread-safe.
  virtual SampledSpectrum radiance(int x, int y, const SampledWavelengths& lambda) const = 0;
  /// The pixel's brightness for importance sampling: its luminance (any positive multiple will do), ≥ 0.
  /// Called once per pixel when the light is built.
  virtual float luminance(int x, int y) const = 0;
  /// ∫ radiance(x, y, λ) dλ over 360-830 nm, by the midpoint rule at 16 wavelengths (four lane groups of
  /// radiance_integral_wavelengths()): a pixel's share of a light's power and sampling weights (W/(m²·sr) for
  /// radiance, W/sr for an intensity image). Called once per pixel when the light is built. The default asks
  /// radiance() four times; an image that upsamples a pixel at each lookup overrides it to upsample once.
  virtual double radiance_integral(int x, int y) const;
  /// radiance_integral(x, y) for every pixel of row y into out[0..width), the same values. Lights call it once per
  /// row when they are built; an image that upsamples per lookup overrides it to evaluate the row one wavelength
  /// group at a time (per-thread basis caches then refill 4 times per row, not 4 times per pixel).
  virtual void radiance_integrals(int y, std::span<double> out) const;
};

/// The four lane groups of wavelengths RadianceImage::radiance_integral's midpoint rule sums, and the width of the
/// band each stands for (nm).
const std::array<SampledWavelengths, 4>& radiance_integral_wavelengths();
double radiance_integral_band_nm();


}  // namespace rimu
