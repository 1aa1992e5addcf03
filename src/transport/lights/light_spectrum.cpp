#include "transport/lights/light_spectrum.h"

#include <cassert>
#include <cmath>

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

LightSpectrum::LightSpectrum(SpectrumPtr shape, double scale) : shape_(std::move(shape)), scale_(scale) {
  assert(shape_ && std::isfinite(scale) && scale >= 0.0 && "a light's scale must be finite and non-negative");
  const int steps = int(kLambdaMaxNm - kLambdaMinNm);
  double sum = 0.5 * (shape_->value(kLambdaMinNm) + shape_->value(kLambdaMaxNm));
  for (int i = 1; i < steps; ++i) sum += shape_->value(kLambdaMinNm + i);
  shape_integral_ = sum;  // × 1 nm
}

}  // namespace rimu
