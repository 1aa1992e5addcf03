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
  subpaths_.clear();
  densities_.clear();
  vertices_.clear();
}

void VertexMergingPass::append(const MergeVertexBatch& batch) {
  const auto subpath_base = uint32_t(subpaths_.size());
  const auto density_base = uint32_t(densities_.size());
  for (MergeSubpath s : batch.subpaths) {
    s.first_density += density_base;
    subpaths_.push_back(s);
  }
  densities_.insert(densities_.end(), batch.densities.begin(), batch.densities.end());
  for (MergeVertex v : batch.vertices) {
    v.subpath += subpath_base;
    vertices_.push_back(v);
  }
}

uint32_t VertexMergingPass::slot_of(int x, int y, int z, int bucket) const {
  uint32_t h = hash32(uint32_t(x) * 73856093u);
  h = hash32(h ^ (uint32_t(y) * 19349663u));
  h = hash32(h ^ (uint32_t(z) * 83492791u));
  h = hash32(h ^ uint32_t(bucket));
  return h & uint32_t(slot_start_.size() - 2);  // the slot count is a power of two
}

void VertexMergingPass::build() {
  // A power of two of slots, at least as many as vertices (a counting sort by slot).
  size_t slots = 1;
  while (slots < std::max<size_t>(vertices_.size(), 1)) slots *= 2;
  slot_start_.assign(slots + 1, 0);
  std::vector<uint32_t> slot(vertices_.size());
  for (size_t i = 0; i < vertices_.size(); ++i) {
    const Vec3 p = vertices_[i].position;
    slot[i] = slot_of(cell_coordinate(p.x), cell_coordinate(p.y), cell_coordinate(p.z), vertices_[i].bucket);
    ++slot_start_[slot[i] + 1];
  }
  for (size_t s = 1; s < slot_start_.size(); ++s) slot_start_[s] += slot_start_[s - 1];
  order_.resize(vertices_.size());
  std::vector<uint32_t> fill(slot_start_.begin(), slot_start_.end() - 1);
  for (size_t i = 0; i < vertices_.size(); ++i) order_[fill[slot[i]]++] = uint32_t(i);
}

int VertexMergingPass::pixel_bucket(int x, int y, int sample_index) const {
  const uint32_t h = hash32(uint32_t(x) * 0x9e3779b9u ^ hash32(uint32_t(y)));
  return int((h + uint32_t(sample_index)) % uint32_t(buckets()));
}

float VertexMergingPass::merge_factor(int bucket) const {
  return std::numbers::pi_v<float> * radius_ * radius_ * float(bucket_subpaths_[size_t(bucket)]);
}

size_t VertexMergingPass::memory_bytes() const {
  return subpaths_.capacity() * sizeof(MergeSubpath) + densities_.capacity() * sizeof(JoinedVertex) +
         vertices_.capacity() * sizeof(MergeVertex) + (slot_start_.capacity() + order_.capacity()) * sizeof(uint32_t);
}

}  // namespace rimu
