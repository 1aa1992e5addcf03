#include "spectral/wavelengths/wavelength_density.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "spectral/spectra/wavelength_range.h"

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

TabulatedWavelengthDensity light_weighted_wavelength_density(const std::function<double(double)>& relative_power,
                                                             const Observer& response, double defensive_fraction) {
  assert(defensive_fraction > 0.0 && defensive_fraction <= 1.0);
  constexpr int kBins = TabulatedWavelengthDensity::kBins;
  constexpr int kSteps = 4;  // the bin mean from its four quarter-centres
  const TabulatedSpectrum* curves[3] = {&response.x_bar, &response.y_bar, &response.z_bar};
  std::vector<double> visible(kBins);
  std::vector<std::array<double, 3>> channel(kBins, {0.0, 0.0, 0.0});
  double visible_total = 0.0;
  std::array<double, 3> channel_total = {0.0, 0.0, 0.0};
  for (int i = 0; i < kBins; ++i) {
    for (int s = 0; s < kSteps; ++s) {
      const double nm = kLambdaMinNm + i + (s + 0.5) / kSteps;
      visible[size_t(i)] += visible_wavelength_pdf(float(nm));
      const double power = relative_power(nm);
      if (!(std::isfinite(power) && power > 0.0)) continue;  // NaN, ∞ and negative emission count as none
      for (int c = 0; c < 3; ++c) channel[size_t(i)][size_t(c)] += power * std::max(curves[c]->value(nm), 0.0);
    }
    visible_total += visible[size_t(i)];
    for (int c = 0; c < 3; ++c) channel_total[size_t(c)] += channel[size_t(i)][size_t(c)];
  }
  std::array<bool, 3> live{};
  int live_channels = 0;
  for (int c = 0; c < 3; ++c) {
    live[size_t(c)] = channel_total[size_t(c)] > 0.0 && std::isfinite(channel_total[size_t(c)]);
    live_channels += live[size_t(c)];
  }
  // No usable emission (a black scene): the visible density alone.
  const double m = live_channels > 0 ? defensive_fraction : 1.0;
  std::vector<double> bins(kBins);
  for (int i = 0; i < kBins; ++i) {
    double light_part = 0.0;
    for (int c = 0; c < 3; ++c)
      if (live[size_t(c)]) light_part += channel[size_t(i)][size_t(c)] / channel_total[size_t(c)] / live_channels;
    bins[size_t(i)] = (1.0 - m) * light_part + m * visible[size_t(i)] / visible_total;
  }
  return TabulatedWavelengthDensity(bins);
}

}  // namespace rimu
