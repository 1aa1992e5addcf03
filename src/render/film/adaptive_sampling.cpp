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
  rays_.assign(n, 0);
  moments_.assign(kMoments * n, 0.0);
  carried_.assign(n, 0.0);
  error_.assign(n, 0.0f);
  relative_squared_.assign(n, INFINITY);
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
// Each pixel's terms are added in ascending order of the neighbour's column (rows pass) and row (columns pass),
// one offset at a time over a whole row, so the loops run over contiguous memory (vectorised) and cost a few
// instructions per pixel and offset; a loop per pixel over its clipped window cost ~200 per pixel, 1 % of a
// window-and-corridor render (callgrind), for the same sums in the same order.
// `rows` is scratch space; `means` receives the result (both resized to the image).
void window_means(const std::vector<double>& values, int w, int h, int r, std::vector<double>& rows,
                  std::vector<double>& means) {
  rows.assign(values.size(), 0.0);
  means.assign(values.size(), 0.0);
  const size_t width = size_t(w);
  for (int y = 0; y < h; ++y) {
    const double* in = &values[size_t(y) * width];
    double* out = &rows[size_t(y) * width];
    for (int d = -r; d <= r; ++d) {  // out[x] += in[x + d] where 0 ≤ x + d < w
      const int x0 = std::max(0, -d), x1 = std::min(w, w - d);
      for (int x = x0; x < x1; ++x) out[x] += in[x + d];
    }
  }
  for (int y = 0; y < h; ++y) {
    double* out = &means[size_t(y) * width];
    for (int v = std::max(0, y - r); v <= std::min(h - 1, y + r); ++v) {
      const double* in = &rows[size_t(v) * width];
      for (size_t x = 0; x < width; ++x) out[x] += in[x];
    }
    const int rows_in_window = std::min(h - 1, y + r) - std::max(0, y - r) + 1;
    for (int x = 0; x < w; ++x) out[x] /= (std::min(w - 1, x + r) - std::max(0, x - r) + 1) * rows_in_window;
  }
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
  // Each pixel's relative variance per sample, the mean over linear R, G, B of its samples' variance over the
  // squared mean (each channel's mean at least kChannelFloor of the largest), from the second moments of its own
  // samples: an estimate with one degree of freedom fewer than the pixel has samples, where the two half buffers'
  // difference has one, however many samples they hold. (With that one, a pass's shares stayed as noisy after
  // 2000 samples as after 32.)
  std::vector<double>& per_sample = scratch_.per_sample;
  per_sample.assign(n, INFINITY);  // +∞: fewer than 2 samples, no estimate
  for (size_t i = 0; i < n; ++i) {
    const double* m = &moments_[kMoments * i];
    const double count = m[6];
    if (count < 2.0) continue;
    double largest = 0.0;
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(m[c] / count));
    double relative = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double mean = m[c] / count, variance = std::max(0.0, (m[3 + c] - m[c] * mean) / (count - 1.0));
      const double floor = std::max(std::abs(mean), kChannelFloor * largest);
      if (variance > 0.0) relative += variance / std::max(floor * floor, 1e-60) / 3.0;
    }
    per_sample[i] = relative;
  }
  // A pixel's target share of the counts is its deviation: the square root of that relative variance (the mean over
  // a (2r + 1)² window, r = allocation_radius_px: a rare bright path in one pixel's samples says its neighbours'
  // can have it too), at least the neighbourhood's floor (update_errors), over the square root of its cost per
  // sample. The cost needs no window: it is a mean over the pixel's samples, and its square root varies little.
  std::vector<double>& deviation = scratch_.deviation;
  deviation.assign(n, -1.0);  // −1: no estimate, the pixel takes a uniform share
  double deviation_sum = 0.0, samples_sum = 0.0;
  const std::vector<double>& window = scratch_.window;
  window_means(per_sample, bounds_.width(), bounds_.height(), settings_.allocation_radius_px, scratch_.rows,
               scratch_.window);
  for (size_t i = 0; i < n; ++i) {
    if (!active_[i]) continue;
    samples_sum += samples_[i];
    const double relative_variance = std::max(window[i], colour_floor_[i] * double(samples_[i]));
    if (!std::isfinite(relative_variance)) continue;
    const double cost = double(rays_[i]) / double(std::max(samples_[i], 1)) + kSampleOverheadRays;
    deviation[i] = std::sqrt(relative_variance / cost);
    deviation_sum += deviation[i];
  }
  // Targets after the pass: the counts, pass included, shared in proportion to the deviations. The pass gives each
  // pixel one sample and the rest to the pixels short of their targets, in proportion to the shortfall.
  const double budget = double(pass_samples) * double(active_count_);
  const double cap = double(settings_.max_pass_share) * pass_samples;
  // Each pixel with an estimate takes 1 sample plus `extra`, up to `room` (the cap per pass, and the maximum spp);
  // the pass's rest is shared out in rounds (water-filling): first in proportion to the pixels' shortfalls from
  // their targets, never past a target; what a capped pixel cannot take goes to the others in the next round; once
  // every target is met, in proportion to the deviations, the targets' own shape. Without the later rounds a pass
  // whose shortfall sat in a few capped pixels spent only part of its budget (as little as two thirds on the Cornell
  // box at 80 × 45), so a time budget ran more, smaller passes (91 against 72 in 10 s there), each giving every
  // pixel its one sample whatever its error.
  std::vector<double>& extra = scratch_.extra;
  std::vector<double>& room = scratch_.room;
  std::vector<double>& shortfall = scratch_.shortfall;
  extra.assign(n, 0.0);
  room.assign(n, 0.0);
  shortfall.assign(n, 0.0);
  double rest = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (!active_[i] || deviation[i] < 0.0) continue;
    room[i] = std::max(0.0, std::min(cap, double(max_spp - samples_[i])) - 1.0);
    rest += double(pass_samples) - 1.0;
    if (deviation_sum > 0.0) {
      const double target = (samples_sum + budget) * deviation[i] / deviation_sum;
      shortfall[i] = std::max(0.0, target - samples_[i] - 1.0);
    }
  }
  for (int phase = 0; phase < 2 && deviation_sum > 0.0; ++phase) {
    // Phase 0: weights are the remaining shortfalls (a pixel takes at most its own); phase 1: the deviations.
    for (int round = 0; round < 8 && rest > 0.5; ++round) {
      double weight_sum = 0.0;
      for (size_t i = 0; i < n; ++i)
        if (extra[i] < room[i]) weight_sum += phase == 0 ? shortfall[i] - extra[i] : deviation[i];
      if (!(weight_sum > 0.0)) break;
      const double scale = phase == 0 ? std::min(1.0, rest / weight_sum) : rest / weight_sum;
      double given = 0.0;
      for (size_t i = 0; i < n; ++i) {
        if (!(extra[i] < room[i])) continue;
        const double add = std::min(scale * (phase == 0 ? shortfall[i] - extra[i] : deviation[i]), room[i] - extra[i]);
        extra[i] += add;
        given += add;
      }
      rest -= given;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    pass_samples_[i] = 0;
    if (!active_[i]) continue;
    // No estimate yet, or no deviation anywhere: a uniform share.
    double share = deviation[i] >= 0.0 && deviation_sum > 0.0 ? 1.0 + extra[i] : double(pass_samples);
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
  std::vector<uint8_t>& converged = scratch_.converged;
  converged.resize(size_t(w) * size_t(h));
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
  std::vector<double>* variance = scratch_.variance;
  std::vector<double>* mean_squared = scratch_.mean_squared;
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
    // Colour, for the floor: linear R, G, B, each channel's mean bounded below by kChannelFloor of the largest.
    double a_rgb[3], b_rgb[3], largest = 0.0;
    for (int c = 0; c < 3; ++c) {
      a_rgb[c] = to_rgb_(c, 0) * a[0] + to_rgb_(c, 1) * a[1] + to_rgb_(c, 2) * a[2];
      b_rgb[c] = to_rgb_(c, 0) * b[0] + to_rgb_(c, 1) * b[1] + to_rgb_(c, 2) * b[2];
      largest = std::max(largest, std::abs(a_rgb[c] + b_rgb[c]));
    }
    const double floor = kChannelFloor * largest / std::max(na + nb, 1e-300);
    for (int c = 0; c < 3; ++c) add(1 + c, i, error_terms(a_rgb[c], b_rgb[c], na, nb, floor), na + nb);
  }
  // The floor (see the header): the neighbourhood's pooled relative variance per sample, Σ variance / Σ mean², over
  // the pixel's own samples, times neighbourhood_share. Pooled, not the mean of the pixels' relative variances: a
  // nearly black pixel's huge relative error does not lift its neighbours'.
  const int r = settings_.neighbourhood_radius_px;
  std::vector<double>* pooled = scratch_.pooled;
  std::vector<double>& means = scratch_.means;
  for (int k = 0; k < 4; ++k) {
    window_means(variance[k], w, h, r, scratch_.rows, pooled[k]);
    window_means(mean_squared[k], w, h, r, scratch_.rows, means);
    for (size_t i = 0; i < n; ++i) pooled[k][i] = pooled[k][i] > 0.0 ? pooled[k][i] / std::max(means[i], 1e-60) : 0.0;
  }
  const std::vector<double>& luminance_window = scratch_.luminance_window;
  window_means(relative_squared_, w, h, 1, scratch_.rows, scratch_.luminance_window);
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
