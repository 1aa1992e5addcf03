#include "spectral/sampled_wavelengths.h"

#include <cmath>

#include "spectral/wavelength_range.h"

namespace rimu {
namespace {

constexpr double kSharpness = 0.0072;  // 1/nm
constexpr double kCentreNm = 538.0;

// CDF(λ) = (tanh(a(λ−c)) − tanh(a(λmin−c))) / N with N = tanh(a(λmax−c)) − tanh(a(λmin−c)).
const double kTanhLow = std::tanh(kSharpness * (kLambdaMinNm - kCentreNm));
const double kTanhHigh = std::tanh(kSharpness * (kLambdaMaxNm - kCentreNm));
const double kNormalisation = kTanhHigh - kTanhLow;

}  // namespace

float visible_wavelength_pdf(float lambda_nm) {
  if (!(lambda_nm >= kLambdaMinNm && lambda_nm <= kLambdaMaxNm)) return 0.0f;
  const double c = std::cosh(kSharpness * (lambda_nm - kCentreNm));
  return float(kSharpness / (kNormalisation * c * c));
}

Float4 visible_wavelength_pdf(Float4 lambda_nm) {
  return Float4(visible_wavelength_pdf(lambda_nm[0]), visible_wavelength_pdf(lambda_nm[1]),
                visible_wavelength_pdf(lambda_nm[2]), visible_wavelength_pdf(lambda_nm[3]));
}

float sample_visible_wavelength(float u) {
  const double lambda = kCentreNm + std::atanh(kTanhLow + double(u) * kNormalisation) / kSharpness;
  // Rounding can land exactly on the upper end for u just below 1; keep the half-open range.
  return float(std::fmin(lambda, std::nextafter(kLambdaMaxNm, 0.0)));
}

SampledWavelengths SampledWavelengths::sample_visible(float u) {
  Float4 lambda, pdf;
  for (int lane = 0; lane < kLaneCount; ++lane) {
    float u_lane = u + float(lane) / kLaneCount;
    if (u_lane >= 1.0f) u_lane -= 1.0f;
    const float l = sample_visible_wavelength(u_lane);
    lambda.set(lane, l);
    pdf.set(lane, visible_wavelength_pdf(l));
  }
  return SampledWavelengths(lambda, pdf);
}

SampledWavelengths SampledWavelengths::sample_uniform(float u, float min_nm, float max_nm) {
  const float span = max_nm - min_nm;
  Float4 lambda;
  for (int lane = 0; lane < kLaneCount; ++lane) {
    float u_lane = u + float(lane) / kLaneCount;
    if (u_lane >= 1.0f) u_lane -= 1.0f;
    lambda.set(lane, min_nm + u_lane * span);
  }
  return SampledWavelengths(lambda, Float4(1.0f / span));
}

void SampledWavelengths::terminate_secondary() {
  if (secondary_terminated()) return;
  pdf_ = Float4(pdf_[0] / kLaneCount, 0.0f, 0.0f, 0.0f);
}

}  // namespace rimu
