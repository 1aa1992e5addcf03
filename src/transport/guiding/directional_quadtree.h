// A piecewise-constant distribution of directions learned from weighted samples: a quadtree over the equal-area
// square of the sphere (transport/sampling/equal_area_square.h), as in the directional part of the SD-tree of
// Müller, Gross & Novák, "Practical Path Guiding for Efficient Light-Transport Simulation" (EGSR 2017, §3-4).
//
// Every node splits its square into four equal quadrants; a quadrant holding more than a fraction
// `subdivision_threshold` of the tree's energy is split again. Because the square map preserves area, a leaf of
// area A covers a solid angle 4π·A and the density inside it is constant: sampling and pdf() agree exactly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "transport/geometry/vector.h"
#include "transport/guiding/guiding_sample.h"

namespace rimu {

struct QuadtreeSettings {
  float subdivision_threshold = 0.01f;  ///< ρ: a quadrant with more than this share of the energy is split
  int max_depth = 16;                   ///< 4⁻¹⁶ of the square: ~0.0003° wide leaves
  /// A quadrant whose energy rests on fewer effective samples, (Σw)²/Σw² of the samples in it, stays a leaf. The
  /// effective count, not the raw one: where light is found rarely (through a door ajar) most samples weigh 0 and a
  /// few lucky ones carry the energy; splitting down onto them would pile the guide onto the exact directions one
  /// path happened to find, which from the rest of the spatial leaf see nothing (docs/transport.md, "Path guiding").
  float min_effective_samples_to_split = 8.0f;
  int max_nodes = 512;                  ///< the memory bound of one tree
};

class DirectionalQuadtree {
 public:
  /// Fits the tree to `samples` (reordered in place). Empty (no energy) when the weights sum to zero.
  static DirectionalQuadtree build(std::vector<DirectionalSample>& samples, const QuadtreeSettings& settings);

  bool empty() const { return nodes_.empty(); }
  /// (Σw)²/Σw² over the samples the tree was fitted to: how many samples its energy effectively rests on.
  float effective_samples() const { return effective_samples_; }
  /// A square point drawn with density pdf_square(); u ∈ [0, 1)².
  Vec2 sample_square(Vec2 u) const;
  /// The density on the square (area measure, integrates to 1 over [0, 1]²); 0 in quadrants that held no energy.
  float pdf_square(Vec2 square) const;
  /// A unit direction drawn from the learned distribution, and its solid-angle density.
  Vec3 sample_direction(Vec2 u) const;
  float pdf_direction(Vec3 direction) const;
  /// The solid-angle density of the direction of square point `square` (pdf_direction without the inverse map:
  /// for a direction just sampled, whose square point is known).
  float pdf_direction_at_square(Vec2 square) const;

  size_t node_count() const { return nodes_.size(); }
  size_t memory_bytes() const { return nodes_.capacity() * sizeof(Node); }

 private:
  struct Node {
    /// Per quadrant (0: x < ½, y < ½; 1: x ≥ ½, y < ½; 2: x < ½, y ≥ ½; 3), 4 × its share of the node's energy:
    /// the factor by which the density inside it exceeds the node's average. They sum to 4, so sampling needs no
    /// total and pdf_square() only multiplies on the way down (fitted once, read at every guided vertex).
    float density[4] = {0, 0, 0, 0};
    uint32_t child[4] = {0, 0, 0, 0};  ///< index of the quadrant's node; 0: the quadrant is a leaf
  };
  std::vector<Node> nodes_;
  float effective_samples_ = 0.0f;
};

}  // namespace rimu
