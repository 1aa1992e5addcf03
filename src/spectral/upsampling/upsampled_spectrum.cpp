#include "spectral/upsampling/upsampled_spectrum.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace rimu {

KnotSamples::KnotSamples(const KnotValues& knots) {
  for (int i = 0; i < kUpsampleKnotCount; ++i) values_[i] = float(knots[i]);
  values_[kUpsampleKnotCount] = values_[kUpsampleKnotCount - 1];
}

double KnotSamples::value(double lambda_nm) const {
  const double x = std::clamp((lambda_nm - kUpsampleFirstKnotNm) / kUpsampleKnotSpacingNm, 0.0,
                              double(kUpsampleKnotCount - 1));
  const int i = std::min(int(x), kUpsampleKnotCount - 1);
  const double t = x - i;
  return values_[i] + t * (double(values_[i + 1]) - values_[i]);
}

KnotValues KnotSamples::knots() const {
  KnotValues out;
  for (int i = 0; i < kUpsampleKnotCount; ++i) out[i] = values_[i];
  return out;
}

float KnotSamples::max_value() const { return *std::max_element(values_.begin(), values_.end()); }
float KnotSamples::min_value() const { return *std::min_element(values_.begin(), values_.end()); }

ReflectanceSpectrum::ReflectanceSpectrum(const KnotValues& knots) : samples_(knots) {
  assert(samples_.min_value() >= 0.0f && samples_.max_value() <= 1.0f);
}

EmissionSpectrum::EmissionSpectrum(const KnotValues& shape, double scale,
                                   std::shared_ptr<const TabulatedSpectrum> illuminant)
    : shape_(shape), scale_(float(scale)), illuminant_(std::move(illuminant)) {}

double EmissionSpectrum::value(double lambda_nm) const {
  if (!illuminant_) return 0.0;
  return double(scale_) * shape_.value(lambda_nm) * illuminant_->value(lambda_nm);
}

double EmissionSpectrum::max_value() const {
  return illuminant_ ? double(scale_) * shape_.max_value() * illuminant_->max_value() : 0.0;
}

std::string EmissionSpectrum::describe() const {
  return "upsampled emission shaped by " + (illuminant_ ? illuminant_->describe() : std::string("nothing"));
}

}  // namespace rimu
