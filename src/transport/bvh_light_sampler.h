// Chooses a light for a shading point by descending a bounding volume hierarchy over every finite light's parts
// (each emissive triangle its own leaf), in proportion to each cluster's importance there (light_bounds.h;
// Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting").
//
// Descent. At an interior node with children a, b of importances I_a, I_b at (p, n), child a is taken with
// probability I_a / (I_a + I_b); the leaf's probability is the product along its path. pmf() retraces that path
// (stored per leaf as a bit trail) and multiplies the same factors in the same order, so it returns exactly the
// sampled probability. Importances are 0 behind one-sided emitters, outside spot/IES cones and below an opaque
// surface's tangent plane.
//
// Pruning. A node's bounds are looser than its children's, so a node can score > 0 while every leaf below it
// scores 0 (its box straddles the tangent plane, each child's box lies below it). A descent into such a subtree
// would find no light, and that probability would be lost (~20 % at random points with random normals). So a
// child's importance counts only if some leaf below it scores > 0. That is decided from the child's own bounds
// where they guarantee that every leaf scores (the usual case: the cluster wholly above the tangent plane and p
// inside every member's emission cone; below such a cluster nothing more is checked), else on the subtree's
// representative (its leaf whose emission reaches the widest cone, then the brightest), else by a depth-first
// search that stops at the first leaf that scores > 0. The leaf found is carried down as a witness: the child
// holding it needs no check, so a descent checks one child per level. The probabilities of the leaves that score
// > 0 then sum to 1 (to float rounding), and no other leaf has any. pmf() carries the same witnesses along the
// same path, so it still multiplies identical factors. Cost: one extra importance evaluation per level where
// nothing is certified; a search only where clusters straddle (docs/benchmarks.md, "Light sampling").
//
// An environment with portals (environment_light.h) is a leaf of the tree: its bounds are the portal rectangles,
// two-sided, with the intensity of a Lambertian emitter of the environment's mean radiance, so near a window the sky
// competes with the lamps as a window-sized area light would, and far from it gets little.
// Other lights at infinity (environment, distant) are not in the tree. Their rule, independent of the scene's size:
// with m of them, each gets probability 1/(m + 1) and the tree the remaining 1/(m + 1), as pbrt-v4 does. Where no
// finite light can contribute (the tree's top split has importance 0 on both sides), each gets 1/m instead.
//
// Build: binned (12 bins per axis) top-down splits minimising Conty & Kulla's surface-area-orientation cost
// Σ_children intensity · M_Ω · area, the area regularised so that collinear point lights still split. Cost
// O(n log n); memory in memory_bytes().
#pragma once

#include <cstdint>
#include <vector>

#include "transport/light_bounds.h"
#include "transport/light_sampler.h"

namespace rimu {

class BvhLightSampler final : public LightSampler {
 public:
  /// Over `lights` (indices as given; they must outlive the sampler).
  explicit BvhLightSampler(std::span<const Light* const> lights);

  std::optional<LightChoice> sample(const LightSamplingPoint& at, float u) const override;
  float pmf(const LightSamplingPoint& at, int light, int part) const override;
  bool chooses_parts() const override { return true; }

  /// Leaves (finite light parts with power), nodes, the deepest leaf, and the bytes the sampler holds.
  int leaf_count() const { return leaf_count_; }
  int node_count() const { return int(nodes_.size()); }
  int max_depth() const { return max_depth_; }
  size_t memory_bytes() const;

 private:
  struct Node {
    LightBounds bounds;
    uint32_t index = 0;  // interior: the second child (the first is the next node); leaf: into leaves_
    uint32_t representative = 0;  // the node of the subtree's leaf likeliest to score (widest reach, brightest)
    bool is_leaf = false;
  };
  struct Leaf {
    int light, part;
  };
  static constexpr uint32_t kNoLeaf = 0xffffffffu;
  static constexpr uint32_t kCertified = 0xfffffffeu;  // a witness meaning: every leaf below scores > 0
  struct Split {
    float first = 0.0f, second = 0.0f;  // the probabilities of the two children; both 0 if neither can contribute
    // Per child: a leaf node below it that scores > 0, kCertified, or kNoLeaf (the child cannot contribute).
    uint32_t first_witness = kNoLeaf, second_witness = kNoLeaf;
  };
  struct BuildItem;

  /// The split at interior node `index`, given `witness`: a leaf node below it known to score > 0 (the child
  /// holding it needs no search), kCertified (no child needs one), or kNoLeaf.
  Split split(uint32_t index, uint32_t witness, const LightSamplingPoint& at) const;
  /// The importance of node `index` at `at` if some leaf below it scores > 0, else 0; `*witness`: such a leaf,
  /// kCertified if the node's bounds show that every leaf below scores, or kNoLeaf.
  float pruned_importance(uint32_t index, const LightSamplingPoint& at, uint32_t* witness) const;
  /// A leaf node below interior node `index` (whose importance is > 0) that scores > 0, or kNoLeaf: the
  /// representative if every leaf is certified to score or it scores, else depth first.
  uint32_t find_scoring_leaf(uint32_t index, const LightSamplingPoint& at) const;
  /// The probability of the tree as a whole and of each light at infinity at `at`.
  struct Shares {
    float tree, each_infinite;
    Split root;  // the root's split, reused by the descent (unset for a one-leaf tree)
  };
  Shares shares(const LightSamplingPoint& at) const;
  uint32_t build(std::vector<BuildItem>& items, size_t begin, size_t end, int depth, uint64_t trail);

  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;
  std::vector<uint32_t> first_part_;  // per light: the index of its part 0 in trails_
  std::vector<uint64_t> trails_;      // per (light, part): 1 << depth | the path's bits (1 = second child); 0: none
  std::vector<int> infinite_lights_;
  std::vector<bool> is_infinite_;
  int leaf_count_ = 0;
  int max_depth_ = 0;
};

}  // namespace rimu
