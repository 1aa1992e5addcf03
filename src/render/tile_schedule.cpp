#include "render/tile_schedule.h"

#include <algorithm>
#include <numeric>

namespace rimu {

const std::vector<size_t>& TileSchedule::order(const std::vector<uint64_t>& planned_samples) {
  const size_t n = order_.size();
  double timed_sum = 0.0;
  size_t timed = 0;
  for (const double s : seconds_per_sample_) {
    if (s > 0.0) {
      timed_sum += s;
      ++timed;
    }
  }
  const double fallback = timed > 0 ? timed_sum / double(timed) : 1.0;
  predicted_.resize(n);
  for (size_t t = 0; t < n; ++t) {
    const double per_sample = seconds_per_sample_[t] > 0.0 ? seconds_per_sample_[t] : fallback;
    predicted_[t] = per_sample * double(t < planned_samples.size() ? planned_samples[t] : 0);
  }
  std::iota(order_.begin(), order_.end(), size_t(0));
  std::stable_sort(order_.begin(), order_.end(), [&](size_t a, size_t b) { return predicted_[a] > predicted_[b]; });
  return order_;
}

}  // namespace rimu
