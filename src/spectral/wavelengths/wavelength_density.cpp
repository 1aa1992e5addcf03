#include "spectral/wavelengths/wavelength_density.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

TabulatedWavelengthDensity::TabulatedWavelengthDensity(const std::vector<double>& bin_weights)
    : pdf_(kBins), cdf_(kBins + 1), guide_(kGuide + 1) {
  assert(bin_weights.size() == size_t(kBins));
  double total = 0.0;
  for (double w : bin_weights) {
    assert(std::isfinite(w) && w >= 0.0);
    total += w;
  }
  assert(total > 0.0);
  // The pdf is taken from the stored CDF's steps, so that sample() and pdf() describe the same density up to the
  // float rounding of the pdf (6e-8 relative); a zero-weight bin has a zero step, is never sampled and has pdf 0.
  // Bins are 1 nm wide, so a step is also the bin's density per nm.
  double running = 0.0;
  cdf_[0] = 0.0;
  for (int i = 0; i < kBins; ++i) {
    running += bin_weights[size_t(i)];
    cdf_[size_t(i) + 1] = running / total;
  }
  cdf_[kBins] = 1.0;
  for (int i = 0; i < kBins; ++i) pdf_[size_t(i)] = float(cdf_[size_t(i) + 1] - cdf_[size_t(i)]);
  // guide_[k]: the bin containing u = k / kGuide, i.e. the last i with cdf_[i] ≤ u (sample() scans on from it).
  int bin = 0;
  for (int k = 0; k <= kGuide; ++k) {
    const double u = double(k) / kGuide;
    while (bin < kBins - 1 && cdf_[size_t(bin) + 1] <= u) ++bin;
    guide_[size_t(k)] = bin;
  }
}

float TabulatedWavelengthDensity::pdf(float lambda_nm) const {
  if (!(lambda_nm >= float(kLambdaMinNm) && lambda_nm < float(kLambdaMaxNm))) return 0.0f;
  const int bin = std::min(int(lambda_nm - float(kLambdaMinNm)), kBins - 1);
  return pdf_[size_t(bin)];
}

float TabulatedWavelengthDensity::sample(float u) const {
  int bin = guide_[size_t(std::min(int(u * float(kGuide)), kGuide))];
  while (bin < kBins - 1 && cdf_[size_t(bin) + 1] <= double(u)) ++bin;
  // Here cdf_[bin] ≤ u < cdf_[bin + 1], so the bin's step is positive; invert the linear CDF within it.
  const float start = float(kLambdaMinNm) + float(bin);
  const double step = cdf_[size_t(bin) + 1] - cdf_[size_t(bin)];
  const float offset = step > 0.0 ? float((double(u) - cdf_[size_t(bin)]) / step) : 0.0f;
  // Rounding may land on the bin's upper edge; stay inside the bin so that pdf() sees the same bin.
  return std::clamp(start + offset, start, std::nextafter(start + 1.0f, start));
}

SampledWavelengths TabulatedWavelengthDensity::sample_wavelengths(float u) const {
  Float4 lambda, pdf;
  for (int lane = 0; lane < kLaneCount; ++lane) {
    const float l = sample(rotated_primary_sample(u, lane));
    lambda.set(lane, l);
    pdf.set(lane, this->pdf(l));
  }
  return SampledWavelengths(lambda, pdf);
}

}  // namespace rimu
