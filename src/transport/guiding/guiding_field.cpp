#include "transport/guiding/guiding_field.h"

#include <algorithm>
#include <cmath>
#include <utility>


namespace rimu {
namespace {

float axis_value(Vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

using GuidingSampleIterator = std::vector<GuidingSample>::iterator;

struct SpatialBuilder {
  const GuidingFieldSettings& settings;
  double split_count = 0.0;
  int leaves_planned = 1;  // leaves the tree will have once the recursion settles (bounded by max_leaves)
  std::vector<DirectionalSample> scratch;
  std::vector<std::pair<GuidingSampleIterator, GuidingSampleIterator>> leaf_ranges;

  // The node at `node` for samples [first, last) inside [lo, hi].
  template <typename Nodes, typename Leaves>
  void build(Nodes& nodes, Leaves& leaves, size_t node, GuidingSampleIterator first, GuidingSampleIterator last, Vec3 lo, Vec3 hi,
             int depth) {
    const Vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const bool split = double(last - first) > split_count && depth < 64 && leaves_planned < settings.max_leaves &&
                       axis_value(extent, axis) > 0.0f;
    if (!split) {
      nodes[node].axis = -1;
      nodes[node].child = uint32_t(leaves.size());
      if (settings.parallax_mixture) {
        // Fitted once the tree is complete (the ranges of finished leaves no longer move).
        leaf_ranges.push_back({first, last});
        leaves.emplace_back();
        return;
      }
      scratch.clear();
      if (last - first >= settings.min_samples_per_leaf)
        for (auto it = first; it != last; ++it) scratch.push_back(it->direction);
      leaves.push_back(DirectionalQuadtree::build(scratch, settings.directions));
      return;
    }
    ++leaves_planned;
    const float middle = 0.5f * (axis_value(lo, axis) + axis_value(hi, axis));
    const GuidingSampleIterator cut =
        std::partition(first, last, [&](const GuidingSample& s) { return axis_value(s.position, axis) < middle; });
    const size_t child = nodes.size();
    nodes[node].axis = int8_t(axis);
    nodes[node].split = middle;
    nodes[node].child = uint32_t(child);
    nodes.emplace_back();
    nodes.emplace_back();
    Vec3 lower_hi = hi, upper_lo = lo;
    (axis == 0 ? lower_hi.x : axis == 1 ? lower_hi.y : lower_hi.z) = middle;
    (axis == 0 ? upper_lo.x : axis == 1 ? upper_lo.y : upper_lo.z) = middle;
    build(nodes, leaves, child, first, cut, lo, lower_hi, depth + 1);
    build(nodes, leaves, child + 1, cut, last, upper_lo, hi, depth + 1);
  }
};

}  // namespace

int facing_of(Vec3 n) {
  const Vec3 a{std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
  return 2 * axis + (axis_value(n, axis) < 0.0f ? 1 : 0);
}

GuidingField GuidingField::build(std::vector<GuidingSample>& samples, int pass_samples_per_pixel,
                                 const GuidingFieldSettings& settings, const LeafLoop& for_each_leaf) {
  GuidingField field;
  field.min_effective_samples_ = settings.min_effective_samples;
  // One tree per facing, each over the bounds of its own vertices (a later pass's vertex outside still finds the
  // nearest leaf, since lookups only compare against split planes). The leaf bound is shared: the trees draw from
  // one budget, in facing order.
  SpatialBuilder builder{settings, settings.split_samples * std::sqrt(double(std::max(pass_samples_per_pixel, 1))),
                         kFacings, {}, {}};
  GuidingSampleIterator first = samples.begin();
  for (int f = 0; f < kFacings; ++f) {
    const GuidingSampleIterator last =
        std::partition(first, samples.end(), [f](const GuidingSample& s) { return s.facing == f; });
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (auto it = first; it != last; ++it) {
      lo = {std::fmin(lo.x, it->position.x), std::fmin(lo.y, it->position.y), std::fmin(lo.z, it->position.z)};
      hi = {std::fmax(hi.x, it->position.x), std::fmax(hi.y, it->position.y), std::fmax(hi.z, it->position.z)};
    }
    if (first == last) lo = hi = Vec3{0, 0, 0};
    field.roots_[f] = uint32_t(field.nodes_.size());
    field.nodes_.emplace_back();
    builder.build(field.nodes_, field.leaves_, field.roots_[f], first, last, lo, hi, 0);
    first = last;
  }
  field.nodes_.shrink_to_fit();
  if (settings.parallax_mixture) {
    field.mixtures_.resize(builder.leaf_ranges.size());
    const auto fit = [&](size_t leaf) {
      const auto [first_sample, last_sample] = builder.leaf_ranges[leaf];
      if (last_sample - first_sample < settings.min_samples_per_leaf) return;
      field.mixtures_[leaf] = VmfMixture::fit({first_sample, last_sample}, settings.mixture);
    };
    if (for_each_leaf)
      for_each_leaf(builder.leaf_ranges.size(), fit);
    else
      for (size_t leaf = 0; leaf < builder.leaf_ranges.size(); ++leaf) fit(leaf);
  }
  return field;
}

LeafGuide GuidingField::distribution_at(Vec3 position, int facing) const {
  if (nodes_.empty()) return {};
  size_t node = roots_[facing];
  while (nodes_[node].axis >= 0)
    node = nodes_[node].child + (axis_value(position, nodes_[node].axis) < nodes_[node].split ? 0 : 1);
  const uint32_t index = nodes_[node].child;
  if (!mixtures_.empty()) {
    const VmfMixture& mixture = mixtures_[index];
    if (mixture.empty() || mixture.effective_samples() < min_effective_samples_) return {};
    return {nullptr, &mixture};
  }
  const DirectionalQuadtree& leaf = leaves_[index];
  if (leaf.empty() || leaf.effective_samples() < min_effective_samples_) return {};
  return {&leaf, nullptr};
}

size_t GuidingField::directional_node_count() const {
  size_t count = 0;
  for (const DirectionalQuadtree& leaf : leaves_) count += leaf.node_count();
  for (const VmfMixture& mixture : mixtures_) count += mixture.lobes().size();
  return count;
}

size_t GuidingField::memory_bytes() const {
  size_t bytes = nodes_.capacity() * sizeof(Node) + leaves_.capacity() * sizeof(DirectionalQuadtree);
  for (const DirectionalQuadtree& leaf : leaves_) bytes += leaf.memory_bytes();
  bytes += mixtures_.capacity() * sizeof(VmfMixture);
  for (const VmfMixture& mixture : mixtures_) bytes += mixture.memory_bytes();
  return bytes;
}

}  // namespace rimu
