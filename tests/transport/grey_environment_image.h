// A grey radiance image for the environment- and area-light tests: radiance = luminance = the pixel value at every
// wavelength, so sampling densities and irradiances can be checked against sums over the pixels.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "transport/lights/radiance_image.h"

namespace rimu::test {

class GreyImage final : public RadianceImage {
 public:
  GreyImage(int w, int h, std::vector<float> values) : w_(w), h_(h), values_(std::move(values)) {}
  int width() const override { return w_; }
  int height() const override { return h_; }
  SampledSpectrum radiance(int x, int y, const SampledWavelengths&) const override { return Float4(at(x, y)); }
  float luminance(int x, int y) const override { return luminance_zero_ ? 0.0f : at(x, y); }
  float at(int x, int y) const { return values_[size_t(y) * size_t(w_) + size_t(x)]; }
  bool luminance_zero_ = false;  // a "deep violet" image: radiance without luminance

 private:
  int w_, h_;
  std::vector<float> values_;
};

}  // namespace rimu::test
