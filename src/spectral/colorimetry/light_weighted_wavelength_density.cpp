#include "spectral/colorimetry/light_weighted_wavelength_density.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

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
