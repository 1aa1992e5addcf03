// The learned incident-light field of path guiding: a spatial binary tree over the points paths visited, whose
// leaves each hold a directional quadtree (transport/guiding/directional_quadtree.h) — the SD-tree of Müller,
// Gross & Novák 2017 ("Practical Path Guiding"). A field is fitted, single-threaded and in a fixed order, to the
// samples of one render pass; the next pass samples from it (docs/transport.md, "Path guiding").
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "transport/geometry/vector.h"
#include "transport/guiding/directional_quadtree.h"
#include "transport/guiding/guiding_sample.h"
#include "transport/guiding/vmf_mixture.h"

namespace rimu {

/// Which way a surface faces: the dominant axis of its normal and its sign (0: +x, 1: −x, 2: +y, … 5: −z).
/// Vertices facing different ways learn separate fields: a floor and the wall beside it see different halves of
/// the sphere, and a leaf that mixed them would send half of the wall's guided rays into the wall.
int facing_of(Vec3 normal);
inline constexpr int kFacings = 6;

struct GuidingFieldSettings {
  /// A spatial leaf holding more than this many samples (times √(samples per pixel of the pass), as Müller et al.'s
  /// c·√(2ᵏ)) is split in two, along its longest side.
  double split_samples = 4000.0;
  int max_leaves = 4096;          ///< the memory bound of the spatial tree
  int min_samples_per_leaf = 32;  ///< fewer and the leaf learns nothing: its vertices stay BSDF-sampled
  /// A leaf whose light rests on fewer effective samples ((Σw)²/Σw², DirectionalQuadtree::effective_samples) does
  /// not guide either: a handful of lucky paths is no estimate of where the light comes from, and guiding by it
  /// costs variance at every bounce (docs/transport.md, "Path guiding").
  float min_effective_samples = 32.0f;
  QuadtreeSettings directions;
  /// Leaves learn a parallax-aware vMF mixture (vmf_mixture.h) instead of a directional quadtree.
  bool parallax_mixture = false;
  VmfMixtureSettings mixture;
};

/// What a leaf learned, for one vertex: a quadtree or a mixture (one of them non-null), or nothing.
struct LeafGuide {
  const DirectionalQuadtree* tree = nullptr;
  const VmfMixture* mixture = nullptr;
  explicit operator bool() const { return tree || mixture; }
};

class GuidingField {
 public:
  /// Fits a field to `samples` (reordered in place) recorded in a pass of `pass_samples_per_pixel` samples.
  /// `for_each_leaf(n, fit)` calls fit(0) … fit(n − 1) in any order or in parallel (the leaves' fits are independent,
  /// so the field is the same either way); by default one after the other. Used for the mixtures' fits.
  using LeafLoop = std::function<void(size_t, const std::function<void(size_t)>&)>;
  static GuidingField build(std::vector<GuidingSample>& samples, int pass_samples_per_pixel,
                            const GuidingFieldSettings& settings, const LeafLoop& for_each_leaf = {});

  /// The directional distribution learned near `position` on surfaces facing `facing`; nullptr where nothing was.
  LeafGuide distribution_at(Vec3 position, int facing) const;

  size_t leaf_count() const { return leaves_.size(); }
  size_t directional_node_count() const;  ///< quadtree nodes, or mixture lobes
  size_t memory_bytes() const;

 private:
  struct Node {
    float split = 0.0f;
    int8_t axis = -1;      ///< −1: a leaf, whose distribution is leaves_[child]
    uint32_t child = 0;    ///< the first child (the second follows it), or the leaf index
  };
  std::vector<Node> nodes_;  ///< kFacings trees: the root of facing f is nodes_[roots_[f]]
  uint32_t roots_[kFacings] = {};
  std::vector<DirectionalQuadtree> leaves_;
  std::vector<VmfMixture> mixtures_;  ///< parallel to leaves_ when the field learns mixtures
  float min_effective_samples_ = 0.0f;
};

}  // namespace rimu
