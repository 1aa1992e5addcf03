#include "render/film/film_tile.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

PixelBounds PixelBounds::intersect(const PixelBounds& o) const {
  PixelBounds r{std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  if (r.empty()) r = {};
  return r;
}

double SpectralBinning::bin_width_nm() const { return count > 0 ? (kLambdaMaxNm - kLambdaMinNm) / count : 0.0; }
double SpectralBinning::bin_start_nm(int bin) const { return kLambdaMinNm + bin * bin_width_nm(); }
double SpectralBinning::bin_centre_nm(int bin) const { return kLambdaMinNm + (bin + 0.5) * bin_width_nm(); }

FilmSampleCounts& FilmSampleCounts::operator+=(const FilmSampleCounts& o) {
  accepted += o.accepted;
  nan += o.nan;
  infinite += o.infinite;
  negative += o.negative;
  clamped += o.clamped;
  return *this;
}

FilmTile::FilmTile(PixelBounds bounds, const SpectralResponse& response, SpectralBinning binning, int light_groups)
    : bounds_(bounds.empty() ? PixelBounds{} : bounds),
      response_(&response),
      binning_(binning),
      light_groups_(light_groups),
      data_(size_t(bounds_.area()) * size_t(doubles_per_pixel()), 0.0) {}

void FilmTile::clear() {
  std::fill(data_.begin(), data_.end(), 0.0);
  counts_ = {};
}

namespace {

// Light groups' share of one sample (FilmTile::add_sample): the same estimator per group, into its channel sums and
// (bin[j] ≥ 0: lane j's spectral bin) its bin sums. Contributions are non-negative and sum to the sample's radiance,
// so a group's values are finite and non-negative whenever the total's are (checked by the caller). Out of line, so
// that a film without groups keeps add_sample's code as it was.
[[gnu::noinline]] void add_group_sums(double* g, int groups, int stride, const SampledSpectrum* group_radiance,
                                      Mask4 live, Float4 live_pdf, float filter_weight, const Response4& c,
                                      const int* bin, double inverse_width) {
  assert(group_radiance);
  const Float4 filter_lanes(filter_weight / float(kLaneCount));
  for (int group = 0; group < groups; ++group, g += stride) {
    const Float4 w = select(live, group_radiance[group] / live_pdf, Float4(0.0f)) * filter_lanes;
    g[0] += double(sum(w * c.x));
    g[1] += double(sum(w * c.y));
    g[2] += double(sum(w * c.z));
    for (int j = 0; j < kLaneCount; ++j)
      if (bin[j] >= 0) g[3 + bin[j]] += double(w[j]) * inverse_width;
  }
}

}  // namespace

void FilmTile::add_sample(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda,
                          float filter_weight, const SampledSpectrum* group_radiance) {
  accumulate(x, y, radiance, lambda, filter_weight, false, group_radiance);
}

void FilmTile::add_splat(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda,
                         float weight, const SampledSpectrum* group_radiance) {
  accumulate(x, y, radiance, lambda, weight, true, group_radiance);
}

void FilmTile::accumulate(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda,
                          float filter_weight, bool splat, const SampledSpectrum* group_radiance) {
  assert(bounds_.contains(x, y));
  const Float4 pdf = lambda.pdf();
  const Mask4 live = pdf != Float4(0.0f);
  // Per-lane weight L_j / p_j, with dead lanes forced to 0 (their radiance may be anything).
  const Float4 lane_value = select(live, radiance / pdf, Float4(0.0f));
  const Float4 live_radiance = select(live, radiance, Float4(0.0f));
  const Float4 live_pdf = select(live, pdf, Float4(1.0f));
  if ((is_nan(live_radiance) | is_nan(live_pdf) | is_nan(lane_value)).any() || std::isnan(filter_weight)) {
    ++counts_.nan;
    return;
  }
  if (!(is_finite(live_radiance) & is_finite(live_pdf) & is_finite(lane_value)).all() ||
      !std::isfinite(filter_weight)) {
    ++counts_.infinite;
    return;
  }
  if ((live_radiance < Float4(0.0f)).any() || (live_pdf < Float4(0.0f)).any()) {
    ++counts_.negative;
    return;
  }
  if (!splat) ++counts_.accepted;

  const Response4 c = response_->evaluate(lambda);
  // The weight the sample's values carry: its filter weight, times the clamp's factor where it applies.
  float value_weight = filter_weight;
  if (max_channel_value_ < INFINITY) {
    const Float4 value = lane_value * Float4(1.0f / float(kLaneCount));
    const float largest = std::max({sum(value * c.x), sum(value * c.y), sum(value * c.z)});
    if (largest > max_channel_value_) {
      value_weight *= max_channel_value_ / largest;
      ++counts_.clamped;
    }
  }
  const Float4 weighted = lane_value * Float4(value_weight / float(kLaneCount));
  double* p = pixel(x, y);
  p[0] += double(sum(weighted * c.x));
  p[1] += double(sum(weighted * c.y));
  p[2] += double(sum(weighted * c.z));
  if (!splat) p[kWeight] += double(filter_weight);
  static constexpr int kNoBins[kLaneCount] = {-1, -1, -1, -1};
  if (binning_.count == 0) {
    if (light_groups_ > 0)
      add_group_sums(p + first_group_sum(), light_groups_, group_stride(), group_radiance, live, live_pdf,
                     value_weight, c, kNoBins, 0.0);
    return;
  }

  // Each live lane's spectral bin (-1: none), for the beauty's bins and then the groups'.
  int bin[kLaneCount] = {-1, -1, -1, -1};
  const double inverse_width = 1.0 / binning_.bin_width_nm();
  for (int j = 0; j < kLaneCount; ++j) {
    if (!live[j]) continue;
    const int b = int(std::floor((lambda.lambda_nm(j) - kLambdaMinNm) * inverse_width));
    if (b < 0 || b >= binning_.count) continue;  // only wavelengths outside 360-830 nm, which nothing samples
    bin[j] = b;
    p[kFirstBin + b] += double(weighted[j]) * inverse_width;
  }
  if (light_groups_ > 0)
    add_group_sums(p + first_group_sum(), light_groups_, group_stride(), group_radiance, live, live_pdf, value_weight,
                   c, bin, inverse_width);
}

}  // namespace rimu
