// Chooses a light for a shading point by descending a bounding volume hierarchy over every finite light's parts
// (each emissive triangle its own leaf), in proportion to each cluster's importance there (light_bounds.h;
// Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting").
//
// Descent, four children at a time. The tree is built binary (below) and descended through its "wide" nodes: a wide
// node's slots are the grandchildren of a binary node (or a child that is a leaf), 2-4 of them, whose importances
// I_j at (p, n) are evaluated together in SSE lanes (light_bounds4.h: bit for bit the scalar light_importance), and
// slot j is taken with probability I_j / Σ I. The leaf's probability is the product along its path. pmf() retraces
// that path (stored per leaf as the binary tree's bit trail: one bit per binary level, so one or two per wide
// level) and multiplies the same factors in the same order, so it returns exactly the sampled probability.
// Importances are 0 behind one-sided emitters, outside spot/IES cones and below an opaque surface's tangent plane.
// Against a binary descent this halves the levels and evaluates four bounds for about the instructions of one
// (docs/transport.md, "What the light tree costs").
//
// Pruning. A node's bounds are looser than its children's, so a node can score > 0 while every leaf below it
// scores 0 (its box straddles the tangent plane, each child's box lies below it). A descent into such a subtree
// would find no light, and that probability would be lost (~20 % at random points with random normals). So a
// slot's importance counts only if some leaf below it scores > 0. That is decided from the child's own bounds
// where they guarantee that every leaf scores (the usual case: the cluster wholly above the tangent plane and p
// inside every member's emission cone; below such a cluster nothing more is checked), else on the subtree's
// representative (its leaf whose emission reaches the widest cone, then the brightest; a wide node keeps its slots'
// representatives' bounds in lanes too, so every slot that needs the check gets it from one light_scores4), else by
// a depth-first search that stops at the first leaf that scores > 0. The leaf found is carried down as a witness:
// the child holding it needs no check, so a descent checks one child per level. The probabilities of the leaves that score
// > 0 then sum to 1 (to float rounding), and no other leaf has any. pmf() carries the same witnesses along the
// same path, so it still multiplies identical factors. Cost: one extra importance evaluation per level where
// nothing is certified; a search only where clusters straddle (docs/benchmarks.md, "Light sampling").
//
// Capped search (an option; search_budget 0, the default, leaves searches unlimited). A search is limited to `search_budget` node visits
// (importance evaluations). If it runs out, the slot counts as if it could contribute, with no witness: the
// descent checks every slot below it again. Where such a child has no scoring leaf below, a descent into it finds
// none and sample() returns std::nullopt: the probabilities then sum to less than 1 at that point, by that child's
// share, but every leaf that scores > 0 still has probability > 0 (a child holding one is never dropped), so the
// choice stays unbiased, and pmf() retraces the same checks with the same budget, so it still equals sample()'s
// probability exactly. The cap bounds a choice's work at about 1 + 4·search_budget importance evaluations per wide
// level (binary depth ≤ 62), whatever the lights; without it a search may visit every node below a child at every level (10⁶
// randomly oriented triangles: the bounds certify nothing). Where bounds certify clusters or representatives score
// (rooms, streets, the Cornell box) searches end within a visit or two and the cap never acts; on 1,050 randomly
// oriented triangles at random points with random normals the probabilities sum to 0.87 on average
// (docs/benchmarks.md, "Light sampling").
//
// An environment with portals (environment_light.h) is a leaf of the tree: its bounds are the portal rectangles,
// two-sided, with the intensity of a Lambertian emitter of the environment's mean radiance, so near a window the sky
// competes with the lamps as a window-sized area light would, and far from it gets little.
// Lights at infinity. Other lights at infinity (environment, distant) are not in the tree. The rule, independent of
// the scene's size: with m of them, each gets probability 1/(m + 1) and the tree the remaining 1/(m + 1), as pbrt-v4
// does (where no finite light can contribute, no leaf scoring > 0, each gets 1/m). Wide ones (environments, skies)
// keep that share: a BSDF-sampled ray that escapes finds them, so MIS covers them well (giving an environment its
// irradiance share made a street under a night sky up to 6× noisier). Directional ones
// (a distant light, the sun: Light::directional_irradiance_w_m2) are found by light sampling only, and share their
// part of the rule with the tree by irradiance at the point: of their and the tree's part R, each gets
//   R · (β/k + (1 − β) · E / (E_T + Σ E⊥)),   β = kInfiniteRuleWeight, k the number of members,
// E a sun's irradiance at normal incidence E⊥ and E_T the tree root's importance at the point (with the normal).
// So the sun gets most samples where it outshines the lamps, the tree where they are near, neither less than β/k
// of R; the probabilities still sum to 1 and pmf() works out the same numbers for the same point. The sun's E
// leaves out the receiver's cosine on purpose: with it (0 where the disc is below the tangent plane, the tree taking
// the sun's share there) the day room's error fell a further 10 % but its cost per sample rose 32 %
// (docs/transport.md, "The sun's share by irradiance"); without it the sun's samples there are rejected below the
// surface before any shadow ray, as under the fixed rule. Whether the tree can contribute is decided as for any child
// of the descent (the root's certificate, else its representative, else a search), not from the root's split, so
// choosing a light at infinity, or weighing a BSDF-sampled ray that escaped (pmf()), costs one or two importance
// evaluations rather than a wide node's; the leaf found is the root split's witness.
//
// Spectral importance (Importance::spectral, "light_sampler": "bvh-spectral"). Each node also holds its intensity
// bound's spectral shape in kBands equal bands over 360-830 nm: band b is the cluster's intensity_w_sr times the
// mean of its members' emission spectra over the band relative to their mean over 360-830 nm (so the bands average
// to intensity_w_sr; a cluster holds the sum of its members'). Given the path's wavelengths, a node's importance is
// its geometric factor (light_importance ÷ intensity_w_sr) times
//   ¼ Σ_k band(λ_k) + kSpectralFloor · intensity_w_sr,
// the mean over the four lanes of the power there (lanes without a density, if any, left out). Two variants were
// measured and dropped (docs/sampling.md): weighing each lane by p_vis(λ_k)/p(λ_k), what it adds to the film under
// "wavelength_density": "lights" (worse: 2.8× higher relMSE than bvh on the red + blue lamps there, 1.6× without),
// and, with those weights, 47 bands of 10 nm (4 % lower relMSE on the red + blue lamps under the visible density,
// at 3× the memory). The sum is symmetric in the lanes, so the probabilities are the same whichever lane is the
// hero: the per-lane light densities of the spectral MIS are all equal, and the
// integrators' MIS needs no change (each lane's technique density includes the same choice probability). The floor
// keeps every leaf that can contribute at some wavelength at probability > 0 whatever the bands say (a band mean
// can be 0 where a tabulated spectrum has one non-zero knot), so the choice stays unbiased; pruning (which leaves
// score > 0) is geometric and unchanged, so the probabilities still sum to 1. Without wavelengths (nullptr in
// LightSamplingPoint) the importance is bvh's. Memory: kBands floats more per node.
//
// Build: binned (12 bins per axis) top-down splits minimising Conty & Kulla's surface-area-orientation cost
// Σ_children intensity · M_Ω · area, the area regularised so that collinear point lights still split. Cost
// O(n log n); memory in memory_bytes().
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "transport/lights/light_bounds.h"
#include "transport/lights/light_bounds4.h"
#include "transport/lights/light_sampler.h"

namespace rimu {

class BvhLightSampler final : public LightSampler {
 public:
  /// What a node's importance weighs light by: radiant intensity over 360-830 nm (bvh), or at the path's
  /// wavelengths (bvh-spectral; see above).
  enum class Importance { broadband, spectral };
  static constexpr int kBands = 16;  ///< 29.4 nm each: 64 bytes per node
  static constexpr float kSpectralFloor = 1e-3f;
  /// The weight of the fixed rule where a sun and the tree split their share (see "Lights at infinity"): of 0.15,
  /// 0.25 and 0.3, 0.15 gave the day room the lowest error (docs/transport.md, "The sun's share by irradiance").
  static constexpr float kInfiniteRuleWeight = 0.15f;

  /// The default search cap (see "Capped search"): none. A cap of 8 visits bounds a choice's work in the worst case
  /// (10⁶ random triangles: 13.4 against 17.0 µs per choice) but wastes probability on empty clusters next to a
  /// large emitter: a receiver 0.3 mm from a 9,024-triangle bulb got a 2.2× larger standard error with it (32 visits:
  /// 1.5×; tests/render/integration_emitter_distance_test.cpp), a worse trade than the worst case's 1.3×.
  static constexpr int kSearchBudget = 0;

  /// Over `lights` (indices as given; they must outlive the sampler). `search_budget`: the cap (default
  /// kSearchBudget), or 0 for unlimited searches, so the probabilities sum to exactly 1 wherever some light can
  /// contribute, at a cost that grows with the lights in the worst case.
  explicit BvhLightSampler(std::span<const Light* const> lights, Importance importance = Importance::broadband,
                           int search_budget = kSearchBudget);

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
    ImportanceBounds bounds;
    uint32_t index = 0;  // interior: the second child (the first is the next node); leaf: into leaves_
    uint32_t representative = 0;  // the node of the subtree's leaf likeliest to score (widest reach, brightest)
    bool is_leaf = false;
  };
  struct Leaf {
    int light, part;
  };
  static constexpr uint32_t kNoLeaf = 0xffffffffu;
  static constexpr uint32_t kCertified = 0xfffffffeu;  // a witness meaning: every leaf below scores > 0
  static constexpr uint32_t kUnknown = 0xfffffffdu;  // a witness meaning: the search ran out (see "Capped search")
  // A node of the 4-wide descent (see "Four children at a time"): up to four children, each a node of the binary
  // tree: the grandchildren of a binary node, or its child where that child is a leaf.
  struct WideNode {
    ImportanceBounds4 bounds;           // of each slot's binary node
    std::array<uint32_t, 4> child{};    // the slot's binary node
    std::array<uint32_t, 4> child_end{};  // one past the last binary node of its subtree (depth-first order)
    std::array<uint32_t, 4> wide{};     // the slot's wide node, or kNoLeaf if the slot is a leaf
    uint8_t count = 0;                  // slots used (2-4)
    uint8_t first_slots = 0;            // slots below the binary node's first child (1 if it is a leaf, else 2)
    uint8_t interior_slots = 0;         // bit j: slot j is not a leaf
    uint32_t representatives = 0;       // if interior_slots != 0: its Representatives in representatives_
  };
  // The representative leaves of a wide node's interior slots (a leaf slot is its own witness), their bounds in
  // lanes, checked for every slot that needs a witness at once. Kept apart from WideNode: about three in five wide
  // nodes have only leaf slots and need none (59 bytes per leaf on a 1,053-triangle scene instead of 155).
  struct Representatives {
    ImportanceBounds4 bounds;
    std::array<uint32_t, 4> node{};
  };
  struct WideSplit {
    // Per slot: its importance where some leaf below it scores, else 0; slot j's probability is weight[j] / sum
    // (one division, for the slot taken: sample() and pmf() divide the same two floats).
    std::array<float, 4> weight{};
    float sum = 0.0f;  // (w0 + w1) + (w2 + w3); not > 0 if no slot can contribute
    // What shows that a scoring slot holds a leaf that scores, for the descent below it: bit j of `certified`: every
    // leaf below slot j scores (kCertified); else bit j of `holder`: it holds `passed_down`, the witness this split
    // was given; else witness[j], the leaf its representative check or search found (leaf slots: none needed).
    int certified = 0, holder = 0;
    uint32_t passed_down = kNoLeaf;
    std::array<uint32_t, 4> witness{kNoLeaf, kNoLeaf, kNoLeaf, kNoLeaf};
    uint32_t witness_of(int j) const {
      if ((certified >> j) & 1) return kCertified;
      if ((holder >> j) & 1) return passed_down;
      return witness[size_t(j)];
    }
  };
  struct BuildItem;
  /// A point with what the spectral importance needs of its wavelengths, worked out once per sample()/pmf():
  /// each lane's band and weight (1/n for the n lanes with a density); spectral = false: the broadband importance.
  struct Query : LightSamplingPoint {
    explicit Query(const LightSamplingPoint& at) : LightSamplingPoint(at), point4(at.position_m, at.normal) {}
    ImportancePoint4 point4;  // position_m and normal in lanes, for the wide nodes
    bool spectral = false;
    std::array<int, 4> band{};
    std::array<float, 4> weight{};
  };
  Query query(const LightSamplingPoint& at) const;

  /// The split at wide node `index`, given `witness`: a leaf node below it known to score > 0 (the slot holding it
  /// needs no search), kCertified (no slot needs one), kNoLeaf or kUnknown.
  WideSplit wide_split(uint32_t index, uint32_t witness, const Query& at) const;
  /// A leaf node below interior node `index` (whose importance is > 0) that scores > 0, or kNoLeaf: the
  /// representative if every leaf is certified to score or it scores, else depth first; kUnknown once `*budget`
  /// node visits are spent (a negative budget never runs out). `representative_checked`: the caller found that the
  /// representative scores 0 (the visit still counts), so it is not checked again.
  uint32_t find_scoring_leaf(uint32_t index, const Query& at, int* budget, bool representative_checked = false) const;
  /// The probability of the tree as a whole and of each light at infinity at `at` (see "Lights at infinity").
  struct Shares {
    float tree = 0.0f;
    float wide = 0.0f;  // each light at infinity without a directional estimate (environments, skies)
    // A directional one (the sun): directional_base + directional_scale · E⊥.
    float directional_base = 0.0f, directional_scale = 0.0f;
    uint32_t root_witness = kNoLeaf;  // what decided that the tree can contribute, for the root's split
  };
  Shares shares(const Query& at) const;
  Shares infinite_shares(const Query& at) const;  // shares() where there are lights at infinity
  /// The probability of light at infinity `k` (an index into infinite_lights_) under `shares`.
  float infinite_probability(size_t k, const Shares& shares) const {
    const float e = directional_irradiance_[k];
    return e > 0.0f ? shares.directional_base + shares.directional_scale * e : shares.wide;
  }
  uint32_t build(std::vector<BuildItem>& items, size_t begin, size_t end, int depth, uint64_t trail);
  /// The wide node over interior binary node `index` and, recursively, those below it; `subtree_end` per binary node.
  uint32_t build_wide(uint32_t index, const std::vector<uint32_t>& subtree_end);
  /// The importance of node `index` at `at` (light_importance, or its spectral form when the sampler is spectral
  /// and `at` carries wavelengths). Zero exactly where light_importance is zero (up to underflow).
  float importance(uint32_t index, const Query& at) const;
  /// `broadband` (light_importance of node `index`, > 0) weighed by the node's bands at the path's wavelengths.
  float spectral_importance(uint32_t index, float broadband, const Query& at) const;

  std::vector<Node> nodes_;
  std::vector<WideNode> wide_nodes_;  // the descent's nodes; [0] over the binary root (none for a one-leaf tree)
  std::vector<Representatives> representatives_;
  // Spectral only: per node, the band intensities (W/sr, averaging to the node's intensity_w_sr).
  std::vector<std::array<float, kBands>> node_bands_;
  std::vector<std::array<float, kBands>> light_bands_;  // during the build only: per light, its band shape
  std::vector<Leaf> leaves_;
  std::vector<uint32_t> first_part_;  // per light: the index of its part 0 in trails_
  std::vector<uint64_t> trails_;      // per (light, part): 1 << depth | the path's bits (1 = second child); 0: none
  ImportanceBounds4 tree_representative4_;  // lane 0: the root's representative (for shares())
  std::vector<int> infinite_lights_;
  // Per light at infinity: a directional one's irradiance at normal incidence E⊥ (> 0), 0 for a wide one.
  std::vector<float> directional_irradiance_;
  int directional_count_ = 0;
  float directional_sum_ = 0.0f;  // Σ E⊥
  std::vector<bool> is_infinite_;
  int search_budget_ = 0;
  int leaf_count_ = 0;
  int max_depth_ = 0;
};

}  // namespace rimu
