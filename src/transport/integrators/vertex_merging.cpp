#include "transport/integrators/vertex_merging.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/sampling/bit_mixing.h"

namespace rimu {

float VertexMergingSettings::radius(int sample_index, float scene_scale) const {
  const float first = radius_m > 0.0f ? radius_m : 0.002f * scene_scale;
  return first * std::pow(float(sample_index + 1), 0.5f * (alpha - 1.0f));
}

void VertexMergingPass::start(float radius_m, std::vector<SampledWavelengths> bucket_wavelengths, int light_subpaths) {
  radius_ = radius_m;
  inverse_cell_ = 1.0f / (2.0f * radius_m);
  wavelengths_ = std::move(bucket_wavelengths);
  light_subpaths_ = light_subpaths;
  bucket_subpaths_.assign(wavelengths_.size(), 0);
  for (int i = 0; i < light_subpaths; ++i) ++bucket_subpaths_[size_t(subpath_bucket(i))];
  for (MergeVertexBatch& batch : batches_) batch.clear();
}

uint32_t VertexMergingPass::slot_of(int x, int y, int z, int bucket) const {
  uint32_t h = hash32(uint32_t(x) * 73856093u);
  h = hash32(h ^ (uint32_t(y) * 19349663u));
  h = hash32(h ^ (uint32_t(z) * 83492791u));
  h = hash32(h ^ uint32_t(bucket));
  return h & uint32_t(slot_start_.size() - 2);  // the slot count is a power of two
}

void VertexMergingPass::build() {
  first_subpath_.assign(1, 0);
  size_t vertices = 0;
  for (const MergeVertexBatch& batch : batches_) {
    first_subpath_.push_back(first_subpath_.back() + uint32_t(batch.stored_start.size()));
    vertices += batch.vertices.size();
  }
  // A power of two of slots, at least as many as vertices (a counting sort by slot).
  size_t slots = 1;
  while (slots < std::max<size_t>(vertices, 1)) slots *= 2;
  slot_start_.assign(slots + 1, 0);
  std::vector<uint32_t> slot;
  slot.reserve(vertices);
  for (const MergeVertexBatch& batch : batches_)
    for (const MergeVertex& v : batch.vertices) {
      const Vec3 p = v.position;
      slot.push_back(slot_of(cell_coordinate(p.x), cell_coordinate(p.y), cell_coordinate(p.z), v.bucket));
      ++slot_start_[slot.back() + 1];
    }
  for (size_t s = 1; s < slot_start_.size(); ++s) slot_start_[s] += slot_start_[s - 1];
  order_.resize(vertices);
  std::vector<uint32_t> fill(slot_start_.begin(), slot_start_.end() - 1);
  size_t i = 0;
  for (const MergeVertexBatch& batch : batches_)
    for (const MergeVertex& v : batch.vertices) order_[fill[slot[i++]]++] = {&v, &batch};
}

const StoredLightVertex* VertexMergingPass::light_subpath(int index, int& length) const {
  // The batch holding it: the last whose first subpath is at most `index`.
  const auto after = std::upper_bound(first_subpath_.begin(), first_subpath_.end(), uint32_t(index));
  const size_t b = size_t(after - first_subpath_.begin()) - 1;
  const MergeVertexBatch& batch = batches_[b];
  const size_t local = size_t(index) - first_subpath_[b];
  const uint32_t begin = batch.stored_start[local];
  const uint32_t end = local + 1 < batch.stored_start.size() ? batch.stored_start[local + 1] : uint32_t(batch.stored.size());
  length = int(end - begin);
  return batch.stored.data() + begin;
}

int VertexMergingPass::pixel_bucket(int x, int y, int sample_index) const {
  const uint32_t h = hash32(uint32_t(x) * 0x9e3779b9u ^ hash32(uint32_t(y)));
  return int((h + uint32_t(sample_index)) % uint32_t(buckets()));
}

float VertexMergingPass::merge_factor(int bucket) const {
  return std::numbers::pi_v<float> * radius_ * radius_ * float(bucket_subpaths_[size_t(bucket)]);
}

size_t VertexMergingPass::memory_bytes() const {
  size_t bytes = (first_subpath_.capacity() + slot_start_.capacity()) * sizeof(uint32_t) + order_.capacity() * sizeof(Entry);
  for (const MergeVertexBatch& b : batches_)
    bytes += b.subpaths.capacity() * sizeof(MergeSubpath) + b.densities.capacity() * sizeof(JoinedVertex) +
             b.vertices.capacity() * sizeof(MergeVertex) + b.stored.capacity() * sizeof(StoredLightVertex) +
             b.stored_start.capacity() * sizeof(uint32_t);
  return bytes;
}

}  // namespace rimu
