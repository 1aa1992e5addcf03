#include "render/film/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "spectral/colour_spaces/rgb_colour_space.h"

namespace rimu {

int adaptive_min_spp(int max_spp) { return std::max(16, max_spp / 8); }

AdaptiveSampling::AdaptiveSampling(const Film& film, const AdaptiveSamplingSettings& settings)
    : bounds_(film.pixel_bounds()),
      settings_(settings),
      camera_film_(film.response().kind() == ResponseKind::camera_rgb),
      to_rgb_(camera_film_ ? Matrix3::identity() : RgbColourSpace::named("srgb-linear").xyz_to_rgb()) {
  const size_t n = size_t(bounds_.area());
  last_channels_.assign(3 * n, 0.0);
  last_weight_.assign(n, 0.0);
  for (int h = 0; h < 2; ++h) {
    half_channels_[h].assign(3 * n, 0.0);
    half_weight_[h].assign(n, 0.0);
  }
  samples_.assign(n, 0);
  pass_samples_.assign(n, 0);
  carried_.assign(n, 0.0);
  error_.assign(n, 0.0f);
  relative_squared_.assign(n, INFINITY);
  colour_squared_.assign(n, INFINITY);
  colour_floor_.assign(n, 0.0);
  active_.assign(n, 1);
  active_count_ = n;
}

namespace {

// The colour error's floor on a channel's mean, as a fraction of the pixel's largest channel: a saturated colour's
// small channels still count (relMSE counts them whole), but a channel near 0 cannot take every sample.
constexpr double kChannelFloor = 0.01;

// A pixel's mean from its half sums a, b over half weights n_a, n_b (see the header): the squared standard error of
// the mean and the squared mean, the latter bounded below by `floor` (0 for a black pixel without variation).
struct ErrorTerms {
  double squared_error = INFINITY;  ///< +∞ with an empty half: no estimate
  double squared_mean = 0.0;
  double relative_squared() const {
    if (squared_error == 0.0) return 0.0;
    return squared_error / std::max(squared_mean, 1e-60);
  }
};

ErrorTerms error_terms(double a_sum, double b_sum, double na, double nb, double floor) {
  if (!(na > 0) || !(nb > 0)) return {};
  const double a = a_sum / na, b = b_sum / nb, mean = std::max(std::abs((a_sum + b_sum) / (na + nb)), floor);
  const double difference = a - b;
  return {difference * difference / ((1.0 / na + 1.0 / nb) * (na + nb)), mean * mean};
}

// The mean of `values` (w × h, row by row) over the (2r + 1)² square around each pixel, clipped to the image.
// Summed directly (rows, then columns: (2r + 1) additions a pixel each way), not from a summed-area table, whose
// differences would lose a dark pixel's small error next to a huge one; a window holding +∞ has the mean +∞.
std::vector<double> window_means(const std::vector<double>& values, int w, int h, int r) {
  std::vector<double> rows(values.size()), means(values.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int u = std::max(0, x - r); u <= std::min(w - 1, x + r); ++u) sum += values[size_t(y) * size_t(w) + size_t(u)];
      rows[size_t(y) * size_t(w) + size_t(x)] = sum;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int v = std::max(0, y - r); v <= std::min(h - 1, y + r); ++v) sum += rows[size_t(v) * size_t(w) + size_t(x)];
      const int count = (std::min(w - 1, x + r) - std::max(0, x - r) + 1) * (std::min(h - 1, y + r) - std::max(0, y - r) + 1);
      means[size_t(y) * size_t(w) + size_t(x)] = sum / count;
    }
  return means;
}

}  // namespace

uint64_t AdaptiveSampling::plan_pass(int pass_samples) {
  const size_t n = active_.size();
  const int max_spp = settings_.max_spp > 0 ? settings_.max_spp : INT32_MAX;
  uint64_t total = 0;
  if (!spreading_) {  // before the minimum: every active pixel takes the pass, as a uniform render would
    for (size_t i = 0; i < n; ++i) {
      pass_samples_[i] = active_[i] ? std::min(pass_samples, max_spp - samples_[i]) : 0;
      total += uint64_t(pass_samples_[i]);
    }
    return total;
  }
  // Each pixel's per-sample relative standard deviation, relative error · sqrt(n): its target share of the counts.
  // The relative error is the root mean square over a (2r + 1)² window (r = allocation_radius_px): each pixel's
  // own is a one-degree-of-freedom estimate, and weights that noisy would cost more than they gain where the
  // difficulty is even.
  std::vector<double> deviation(n, -1.0);  // −1: no estimate (one half empty), the pixel takes a uniform share
  double deviation_sum = 0.0, samples_sum = 0.0;
  const std::vector<double> colour_window =
      window_means(colour_squared_, bounds_.width(), bounds_.height(), settings_.allocation_radius_px);
  for (size_t i = 0; i < n; ++i) {
    if (!active_[i]) continue;
    samples_sum += samples_[i];
    const double squared = std::max(colour_window[i], colour_floor_[i]);  // the neighbourhood's floor: update_errors
    if (std::isfinite(squared)) {
      deviation[i] = std::sqrt(squared * double(samples_[i]));
      deviation_sum += deviation[i];
    }
  }
  // Targets after the pass: the counts, pass included, shared in proportion to the deviations. The pass gives each
  // pixel one sample and the rest to the pixels short of their targets, in proportion to the shortfall.
  const double budget = double(pass_samples) * double(active_count_);
  const double rest = std::max(0.0, budget - double(active_count_));
  std::vector<double> shortfall(n, 0.0);
  double shortfall_sum = 0.0;
  if (deviation_sum > 0.0)
    for (size_t i = 0; i < n; ++i) {
      if (!active_[i] || deviation[i] < 0.0) continue;
      const double target = (samples_sum + budget) * deviation[i] / deviation_sum;
      shortfall[i] = std::max(0.0, target - samples_[i] - 1.0);
      shortfall_sum += shortfall[i];
    }
  const double cap = double(settings_.max_pass_share) * pass_samples;
  for (size_t i = 0; i < n; ++i) {
    pass_samples_[i] = 0;
    if (!active_[i]) continue;
    double share = double(pass_samples);  // no estimate, or no pixel short of its target: a uniform share
    if (deviation[i] >= 0.0 && shortfall_sum > 0.0) share = 1.0 + rest * shortfall[i] / shortfall_sum;
    share = std::min({share, cap, double(max_spp - samples_[i])});
    const double owed = carried_[i] + share;
    pass_samples_[i] = int(std::floor(owed));
    carried_[i] = owed - pass_samples_[i];
    total += uint64_t(pass_samples_[i]);
  }
  return total;
}

size_t AdaptiveSampling::after_pass(const Film& film, int samples_end) {
  samples_end_ = samples_end;
  const int half = passes_++ % 2;
  for (int y = bounds_.y0; y < bounds_.y1; ++y)
    for (int x = bounds_.x0; x < bounds_.x1; ++x) {
      const size_t i = index(x, y);
      if (!active_[i]) continue;
      const double* sums = film.accumulators(x, y);
      for (size_t c = 0; c < 3; ++c) {
        half_channels_[half][3 * i + c] += sums[c] - last_channels_[3 * i + c];
        last_channels_[3 * i + c] = sums[c];
      }
      const double weight = film.weight_sum(x, y);
      half_weight_[half][i] += weight - last_weight_[i];
      last_weight_[i] = weight;
      samples_[i] += pass_samples_[i];
      pass_samples_[i] = 0;
    }
  update_errors();
  const bool past_minimum = samples_end >= settings_.min_spp && passes_ >= 2;
  if (past_minimum) spreading_ = true;

  // Converged: the 3×3 error at or under the threshold. Stopped: converged along with its whole neighbourhood, or
  // at the maximum.
  const int w = bounds_.width(), h = bounds_.height(), r = settings_.dilation_px;
  std::vector<uint8_t> converged(size_t(w) * size_t(h));
  for (size_t i = 0; i < converged.size(); ++i) converged[i] = error_[i] <= float(settings_.noise_threshold);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      if (!active_[i]) continue;
      bool all = past_minimum;
      for (int v = std::max(0, y - r); all && v <= std::min(h - 1, y + r); ++v)
        for (int u = std::max(0, x - r); all && u <= std::min(w - 1, x + r); ++u)
          all = converged[size_t(v) * size_t(w) + size_t(u)] != 0;
      if (all || (settings_.max_spp > 0 && samples_[i] >= settings_.max_spp)) {
        active_[i] = 0;
        --active_count_;
      }
    }
  return active_count_;
}

int AdaptiveSampling::max_samples() const {
  return samples_.empty() ? 0 : *std::max_element(samples_.begin(), samples_.end());
}

double AdaptiveSampling::mean_samples() const {
  double sum = 0.0;
  for (int s : samples_) sum += s;
  return samples_.empty() ? 0.0 : sum / double(samples_.size());
}

void AdaptiveSampling::update_errors() {
  const int w = bounds_.width(), h = bounds_.height();
  const size_t n = relative_squared_.size();
  // Each pixel's variance per sample (SE² · n) and squared mean, for the neighbourhood's floor: luminance, then
  // linear R, G, B. A pixel without an estimate yet (an empty half) adds nothing to them.
  std::vector<double> variance[4], mean_squared[4];
  for (int k = 0; k < 4; ++k) {
    variance[k].assign(n, 0.0);
    mean_squared[k].assign(n, 0.0);
  }
  auto add = [&](int k, size_t i, const ErrorTerms& terms, double samples) {
    if (!std::isfinite(terms.squared_error)) return;
    variance[k][i] = terms.squared_error * samples;
    mean_squared[k][i] = terms.squared_mean;
  };
  for (size_t i = 0; i < n; ++i) {
    const double na = half_weight_[0][i], nb = half_weight_[1][i];
    const double* a = &half_channels_[0][3 * i];
    const double* b = &half_channels_[1][3 * i];
    // Luminance: Y of an XYZ film, R + G + B of a camera film.
    const double a_luminance = camera_film_ ? a[0] + a[1] + a[2] : a[1];
    const double b_luminance = camera_film_ ? b[0] + b[1] + b[2] : b[1];
    const ErrorTerms luminance = error_terms(a_luminance, b_luminance, na, nb, 0.0);
    relative_squared_[i] = luminance.relative_squared();
    add(0, i, luminance, na + nb);
    // Colour: the mean over linear R, G, B, each channel's mean bounded below by kChannelFloor of the largest.
    double a_rgb[3], b_rgb[3], largest = 0.0;
    for (int c = 0; c < 3; ++c) {
      a_rgb[c] = to_rgb_(c, 0) * a[0] + to_rgb_(c, 1) * a[1] + to_rgb_(c, 2) * a[2];
      b_rgb[c] = to_rgb_(c, 0) * b[0] + to_rgb_(c, 1) * b[1] + to_rgb_(c, 2) * b[2];
      largest = std::max(largest, std::abs(a_rgb[c] + b_rgb[c]));
    }
    const double floor = kChannelFloor * largest / std::max(na + nb, 1e-300);
    double colour = 0.0;
    for (int c = 0; c < 3; ++c) {
      const ErrorTerms channel = error_terms(a_rgb[c], b_rgb[c], na, nb, floor);
      colour += channel.relative_squared() / 3.0;
      add(1 + c, i, channel, na + nb);
    }
    colour_squared_[i] = colour;
  }
  // The floor (see the header): the neighbourhood's pooled relative variance per sample, Σ variance / Σ mean², over
  // the pixel's own samples, times neighbourhood_share. Pooled, not the mean of the pixels' relative variances: a
  // nearly black pixel's huge relative error does not lift its neighbours'.
  const int r = settings_.neighbourhood_radius_px;
  std::vector<double> pooled[4];
  for (int k = 0; k < 4; ++k) {
    pooled[k] = window_means(variance[k], w, h, r);
    const std::vector<double> means = window_means(mean_squared[k], w, h, r);
    for (size_t i = 0; i < n; ++i) pooled[k][i] = pooled[k][i] > 0.0 ? pooled[k][i] / std::max(means[i], 1e-60) : 0.0;
  }
  const std::vector<double> luminance_window = window_means(relative_squared_, w, h, 1);
  for (size_t i = 0; i < n; ++i) {
    const double samples = half_weight_[0][i] + half_weight_[1][i];
    // No samples: no floor (the pixel has no estimate, its own error is +∞).
    const double share = samples > 0.0 ? settings_.neighbourhood_share / samples : 0.0;
    colour_floor_[i] = share * (pooled[1][i] + pooled[2][i] + pooled[3][i]) / 3.0;
    const double rms = std::sqrt(std::max(luminance_window[i], share * pooled[0][i]));
    error_[i] = std::isfinite(rms) ? float(std::min(rms, 3.0e38)) : 3.0e38f;
  }
}

}  // namespace rimu
