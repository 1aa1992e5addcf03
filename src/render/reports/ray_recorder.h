// Counting and recording the renderer's ray queries, and replaying them through the geometry alone: the
// "throughput ceiling" of issues 4 and 7 (how many rays per second Embree traces when nothing else runs).
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "transport/geometry/ray.h"
#include "transport/integrators/ray_queries.h"
#include "transport/geometry/surface_hit.h"

namespace rimu {

/// Which query a ray was traced with.
enum class RayKind : uint8_t { intersect, occluded };

/// One query as the integrator issued it, with its answer (so a replay can check it traced the same ray).
struct RecordedRay {
  Ray ray;
  RayKind kind = RayKind::intersect;
  bool hit = false;  ///< intersect(): a surface was found; occluded(): the ray is blocked
};

/// Query counts, summed over threads.
struct RayCounts {
  uint64_t intersect = 0, intersect_hits = 0;
  uint64_t occluded = 0, occluded_hits = 0;
  uint64_t total() const { return intersect + occluded; }
};

/// A RayQueries decorator: forwards every query unchanged to `inner` and counts it (and, in record mode, appends
/// it to a buffer owned by the calling thread, so threads never share a cache line or a lock). It returns exactly
/// what `inner` returns, so a render through it is bit-identical to a render without it.
///
/// Cost: one thread-local lookup per query (tbb::enumerable_thread_specific), plus 36 bytes per query when
/// recording. Counters must be read (counts(), take_recording()) only when no query is running.
class RecordingRayQueries final : public RayQueries {
 public:
  enum class Mode { count, record };
  RecordingRayQueries(const RayQueries& inner, Mode mode) : inner_(inner), mode_(mode) {}

  std::optional<SurfaceHit> intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;

  /// The counts since construction or the last reset().
  RayCounts counts() const;
  /// Moves the per-thread buffers out (no copy; within a buffer, rays are in the order that thread issued them).
  std::vector<std::vector<RecordedRay>> take_recording();
  /// Zeroes the counts and drops any recording.
  void reset();

 private:
  struct alignas(64) PerThread {
    RayCounts counts;
    std::vector<RecordedRay> rays;
  };
  const RayQueries& inner_;
  Mode mode_;
  mutable tbb::enumerable_thread_specific<PerThread> per_thread_;
};

/// What a replay measured.
struct ReplayResult {
  uint64_t rays = 0;
  double seconds = 0;
  uint64_t mismatches = 0;  ///< answers (hit or not) that differ from the recorded ones: 0 for the same geometry
};

/// Traces every recorded ray through `geometry` (its intersect() or occluded(), as recorded) with oneTBB over
/// chunks of each buffer, at whatever parallelism the caller allows (tbb::global_control), and times it.
ReplayResult replay_rays(const RayQueries& geometry, const std::vector<std::vector<RecordedRay>>& recording);

}  // namespace rimu
