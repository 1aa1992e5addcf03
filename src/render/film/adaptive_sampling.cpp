#include "render/film/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

namespace rimu {

int adaptive_min_spp(int max_spp) { return std::max(16, max_spp / 8); }

AdaptiveSampling::AdaptiveSampling(const Film& film, const AdaptiveSamplingSettings& settings)
    : bounds_(film.pixel_bounds()),
      settings_(settings),
      camera_film_(film.response().kind() == ResponseKind::camera_rgb) {
  const size_t n = size_t(bounds_.area());
  last_luminance_.assign(n, 0.0);
  last_weight_.assign(n, 0.0);
  for (int h = 0; h < 2; ++h) {
    half_luminance_[h].assign(n, 0.0);
    half_weight_[h].assign(n, 0.0);
  }
  samples_.assign(n, 0);
  error_.assign(n, 0.0f);
  active_.assign(n, 1);
  active_count_ = n;
}

double AdaptiveSampling::luminance_sum(const Film& film, int x, int y) const {
  const double* sums = film.accumulators(x, y);
  return camera_film_ ? sums[0] + sums[1] + sums[2] : sums[1];
}

size_t AdaptiveSampling::after_pass(const Film& film, int samples_end) {
  const int pass_samples = samples_end - samples_end_;
  samples_end_ = samples_end;
  const int half = passes_++ % 2;
  for (int y = bounds_.y0; y < bounds_.y1; ++y)
    for (int x = bounds_.x0; x < bounds_.x1; ++x) {
      const size_t i = index(x, y);
      if (!active_[i]) continue;
      const double luminance = luminance_sum(film, x, y), weight = film.weight_sum(x, y);
      half_luminance_[half][i] += luminance - last_luminance_[i];
      half_weight_[half][i] += weight - last_weight_[i];
      last_luminance_[i] = luminance;
      last_weight_[i] = weight;
      samples_[i] += pass_samples;
    }
  update_errors();
  if (samples_end < settings_.min_spp || passes_ < 2) return active_count_;

  // Converged: the 3×3 error at or under the threshold. Stopped: converged along with its whole neighbourhood.
  const int w = bounds_.width(), h = bounds_.height(), r = settings_.dilation_px;
  std::vector<uint8_t> converged(size_t(w) * size_t(h));
  for (size_t i = 0; i < converged.size(); ++i) converged[i] = error_[i] <= float(settings_.noise_threshold);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t& a = active_[size_t(y) * size_t(w) + size_t(x)];
      if (!a) continue;
      bool all = true;
      for (int v = std::max(0, y - r); all && v <= std::min(h - 1, y + r); ++v)
        for (int u = std::max(0, x - r); all && u <= std::min(w - 1, x + r); ++u)
          all = converged[size_t(v) * size_t(w) + size_t(u)] != 0;
      if (all) {
        a = 0;
        --active_count_;
      }
    }
  return active_count_;
}

void AdaptiveSampling::update_errors() {
  const int w = bounds_.width(), h = bounds_.height();
  std::vector<double> relative_squared(size_t(w) * size_t(h), 0.0);
  for (size_t i = 0; i < relative_squared.size(); ++i) {
    const double na = half_weight_[0][i], nb = half_weight_[1][i];
    if (!(na > 0) || !(nb > 0)) {
      relative_squared[i] = INFINITY;  // one half empty: no estimate yet
      continue;
    }
    const double a = half_luminance_[0][i] / na, b = half_luminance_[1][i] / nb;
    const double mean = (half_luminance_[0][i] + half_luminance_[1][i]) / (na + nb);
    const double standard_error = std::abs(a - b) / std::sqrt((1.0 / na + 1.0 / nb) * (na + nb));
    const double relative = standard_error == 0.0 ? 0.0 : standard_error / std::max(std::abs(mean), 1e-30);
    relative_squared[i] = relative * relative;
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      int count = 0;
      for (int v = std::max(0, y - 1); v <= std::min(h - 1, y + 1); ++v)
        for (int u = std::max(0, x - 1); u <= std::min(w - 1, x + 1); ++u, ++count)
          sum += relative_squared[size_t(v) * size_t(w) + size_t(u)];
      const double rms = std::sqrt(sum / count);
      error_[size_t(y) * size_t(w) + size_t(x)] = std::isfinite(rms) ? float(std::min(rms, 3.0e38)) : 3.0e38f;
    }
}

}  // namespace rimu
