// The order in which a pass hands its tiles to the threads: the most costly first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rimu {

/// A pass ends when its last tile does. Handed out in image order, a costly tile that comes late (the corridor of a
/// room whose window is bright, where adaptive sampling puts 18 % of a pass into one of fifteen tiles) keeps one
/// thread busy while the others wait: at 80 × 45 on 2 threads that was ~10 % of every pass's wall time. Handing out
/// the costliest first (Graham's "longest processing time first" rule) leaves only small tiles for the end.
///
/// A tile's cost in the next pass is predicted from its last pass: its seconds per sample there times the samples
/// it takes now (a uniform pass: the same for every tile; an adaptive one: the sum of its pixels' counts). Timing
/// decides only the order; each tile's samples and results do not depend on it (the renderer merges tiles in their
/// image order), so the image stays the same for any order, any thread count and any timing.
class TileSchedule {
 public:
  explicit TileSchedule(size_t tiles) : seconds_per_sample_(tiles, 0.0), order_(tiles) {}

  /// The order for a pass in which tile t takes planned_samples[t] samples: descending predicted cost, ties (and
  /// tiles never timed, e.g. before the first pass) in image order. A tile not timed yet is predicted at the mean
  /// seconds per sample of the tiles that were.
  const std::vector<size_t>& order(const std::vector<uint64_t>& planned_samples);

  /// After tile t's part of a pass: its wall seconds and the samples it took (a tile of 0 samples says nothing).
  /// Tiles are disjoint, so threads record different t.
  void record(size_t t, double seconds, uint64_t samples) {
    if (samples > 0) seconds_per_sample_[t] = seconds / double(samples);
  }

 private:
  std::vector<double> seconds_per_sample_;  ///< 0: not timed yet
  std::vector<size_t> order_;
  std::vector<double> predicted_;
};

}  // namespace rimu
