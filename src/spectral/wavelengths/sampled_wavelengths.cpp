#include "spectral/wavelengths/sampled_wavelengths.h"

#include <algorithm>
#include <cmath>

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {
namespace {

constexpr double kSharpness = 0.0072;  // 1/nm
constexpr double kCentreNm = 538.0;

// CDF(λ) = (tanh(a(λ−c)) − tanh(a(λmin−c))) / N with N = tanh(a(λmax−c)) − tanh(a(λmin−c)).
const double kTanhLow = std::tanh(kSharpness * (kLambdaMinNm - kCentreNm));
const double kTanhHigh = std::tanh(kSharpness * (kLambdaMaxNm - kCentreNm));
const double kNormalisation = kTanhHigh - kTanhLow;

// The per-sample path runs in float with one exponential or one logarithm per lane: every camera sample draws
// four wavelengths and their pdfs, and double-precision cosh/atanh cost ~65 ns a lane (docs/benchmarks.md,
// "Colour-science core"). Float keeps the CDF within ~3e-7 of the exact one (tests/spectral/
// sampled_wavelengths_test.cpp integrates the pdf to check it), far below any Monte Carlo noise.
const float kTwoSharpness = float(2.0 * kSharpness);
const float kHalfOverSharpness = float(0.5 / kSharpness);
const float kPdfScale = float(4.0 * kSharpness / kNormalisation);
const float kTanhLowF = float(kTanhLow);
const float kNormalisationF = float(kNormalisation);
const float kLambdaMaxBelow = std::nextafter(float(kLambdaMaxNm), 0.0f);

}  // namespace

float visible_wavelength_pdf(float lambda_nm) {
  if (!(lambda_nm >= kLambdaMinNm && lambda_nm <= kLambdaMaxNm)) return 0.0f;
  // a / (N cosh²(x)) with x = a(λ − c), written with one exponential: 1/cosh²(x) = 4e^{2x} / (e^{2x} + 1)².
  // e^{2x} stays within [e^{-2.6}, e^{4.3}]: no overflow, no cancellation.
  const float e = std::exp(kTwoSharpness * (lambda_nm - float(kCentreNm)));
  return kPdfScale * e / ((e + 1.0f) * (e + 1.0f));
}

Float4 visible_wavelength_pdf(Float4 lambda_nm) {
  return Float4(visible_wavelength_pdf(lambda_nm[0]), visible_wavelength_pdf(lambda_nm[1]),
                visible_wavelength_pdf(lambda_nm[2]), visible_wavelength_pdf(lambda_nm[3]));
}

float sample_visible_wavelength(float u) {
  // λ = c + atanh(t)/a with t = tanh(a(λmin − c)) + u·N, and atanh(t) = ½ log((1 + t)/(1 − t)). t lies in
  // [−0.86, 0.97], so 1 − t is exact in float (Sterbenz) and never small.
  const float t = kTanhLowF + u * kNormalisationF;
  const float lambda = float(kCentreNm) + std::log((1.0f + t) / (1.0f - t)) * kHalfOverSharpness;
  // Rounding can step just outside the ends for u near 0 or 1; keep the half-open range.
  return std::clamp(lambda, float(kLambdaMinNm), kLambdaMaxBelow);
}

SampledWavelengths SampledWavelengths::sample_visible(float u) {
  Float4 lambda, pdf;
  for (int lane = 0; lane < kLaneCount; ++lane) {
    const float l = sample_visible_wavelength(rotated_primary_sample(u, lane));
    lambda.set(lane, l);
    pdf.set(lane, visible_wavelength_pdf(l));
  }
  return SampledWavelengths(lambda, pdf);
}

SampledWavelengths SampledWavelengths::sample_uniform(float u, float min_nm, float max_nm) {
  const float span = max_nm - min_nm;
  Float4 lambda;
  for (int lane = 0; lane < kLaneCount; ++lane) lambda.set(lane, min_nm + rotated_primary_sample(u, lane) * span);
  return SampledWavelengths(lambda, Float4(1.0f / span));
}

void SampledWavelengths::terminate_secondary() {
  if (secondary_terminated()) return;
  pdf_ = Float4(pdf_[0] / kLaneCount, 0.0f, 0.0f, 0.0f);
}

}  // namespace rimu
