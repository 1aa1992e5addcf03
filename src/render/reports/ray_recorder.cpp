#include "render/reports/ray_recorder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <utility>

namespace rimu {

std::optional<SurfaceHit> RecordingRayQueries::intersect(const Ray& ray) const {
  std::optional<SurfaceHit> hit = inner_.intersect(ray);
  PerThread& local = per_thread_.local();
  ++local.counts.intersect;
  local.counts.intersect_hits += hit.has_value();
  if (mode_ == Mode::record) local.rays.push_back({ray, RayKind::intersect, hit.has_value()});
  return hit;
}

bool RecordingRayQueries::occluded(const Ray& ray) const {
  const bool blocked = inner_.occluded(ray);
  PerThread& local = per_thread_.local();
  ++local.counts.occluded;
  local.counts.occluded_hits += blocked;
  if (mode_ == Mode::record) local.rays.push_back({ray, RayKind::occluded, blocked});
  return blocked;
}

RayCounts RecordingRayQueries::counts() const {
  RayCounts sum;
  for (const PerThread& t : per_thread_) {
    sum.intersect += t.counts.intersect;
    sum.intersect_hits += t.counts.intersect_hits;
    sum.occluded += t.counts.occluded;
    sum.occluded_hits += t.counts.occluded_hits;
  }
  return sum;
}

std::vector<std::vector<RecordedRay>> RecordingRayQueries::take_recording() {
  std::vector<std::vector<RecordedRay>> buffers;
  for (PerThread& t : per_thread_)
    if (!t.rays.empty()) buffers.push_back(std::exchange(t.rays, {}));
  return buffers;
}

void RecordingRayQueries::reset() { per_thread_.clear(); }

ReplayResult replay_rays(const RayQueries& geometry, const std::vector<std::vector<RecordedRay>>& recording) {
  // Chunks of consecutive rays of one buffer: large enough that scheduling costs nothing next to traversal, and
  // consecutive so a chunk keeps the order (and the memory locality) in which one render thread traced its paths.
  constexpr size_t kChunk = 4096;
  struct Chunk {
    const RecordedRay* begin;
    const RecordedRay* end;
  };
  std::vector<Chunk> chunks;
  ReplayResult result;
  for (const auto& buffer : recording) {
    result.rays += buffer.size();
    for (size_t i = 0; i < buffer.size(); i += kChunk)
      chunks.push_back({buffer.data() + i, buffer.data() + std::min(i + kChunk, buffer.size())});
  }

  const auto start = std::chrono::steady_clock::now();
  result.mismatches = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, chunks.size(), 1), uint64_t(0),
      [&](const tbb::blocked_range<size_t>& range, uint64_t mismatches) {
        for (size_t c = range.begin(); c != range.end(); ++c) {
          for (const RecordedRay* r = chunks[c].begin; r != chunks[c].end; ++r) {
            const bool hit = r->kind == RayKind::intersect ? geometry.intersect(r->ray).has_value()
                                                           : geometry.occluded(r->ray);
            mismatches += hit != r->hit;
          }
        }
        return mismatches;
      },
      [](uint64_t a, uint64_t b) { return a + b; });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace rimu
