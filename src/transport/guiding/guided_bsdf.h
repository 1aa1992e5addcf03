// A BSDF combined with a learned directional distribution by one-sample MIS (the balance heuristic): a direction is
// drawn from the guide with probability α, else from the BSDF, and its density is the mixture's,
// α·p_guide + (1 − α)·p_bsdf, per lane. Every density the path integrator uses for a BSDF-sampled direction (the
// throughput, the spectral MIS ratios and the weight against next-event estimation) is this one, so the estimator
// stays unbiased whatever the guide learned — as long as the BSDF covers every direction the guide does not.
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf.h"
#include "transport/geometry/frame.h"
#include "transport/guiding/directional_quadtree.h"
#include "transport/guiding/guiding_field.h"
#include "transport/guiding/vmf_mixture.h"

namespace rimu {

/// The guide at one vertex: a leaf's quadtree, or its mixture re-aimed from the vertex (VmfMixture::at), or none.
class VertexGuide {
 public:
  VertexGuide() = default;
  VertexGuide(const LeafGuide& leaf, Vec3 position) : tree_(leaf.tree), has_mixture_(leaf.mixture != nullptr) {
    if (has_mixture_) mixture_ = leaf.mixture->at(position);
  }
  explicit operator bool() const { return tree_ || has_mixture_; }
  /// A world direction and its solid-angle density; u_select ∈ [0, 1) picks a mixture's lobe.
  Vec3 sample(float u_select, Vec2 u, float& pdf) const;
  float pdf(Vec3 direction) const;

 private:
  const DirectionalQuadtree* tree_ = nullptr;
  bool has_mixture_ = false;
  VertexMixture mixture_;
};

/// Which surface vertices are guided: a BSDF with a non-delta lobe and no delta one (a delta lobe cannot be
/// evaluated, so no mixture density exists), and not a pane the path passes straight through (no vertex at all).
/// The path integrators and the daylit points (daylit_connection.h) all decide by this and find the leaf by
/// guide_leaf_at, because a guided density must be the same function of the vertex wherever it is evaluated: a
/// technique that guided a vertex the path's own sampling did not would be weighted wrongly (docs/benchmarks.md,
/// "Path guiding", fifth round: such a mismatch came out 57 % too bright).
inline bool is_guidable(const BsdfFlags& flags, bool passes_through) {
  return flags.has_non_delta && !flags.has_delta && !passes_through;
}

/// The learned guide of a guidable vertex at `position` whose geometric normal `ng` is on the side its BSDF's frame
/// faces (the side it is seen from, or for a transmissive BSDF as the surface gives it); none without a field.
inline LeafGuide guide_leaf_at(const GuidingField* field, Vec3 position, Vec3 ng) {
  return field ? field->distribution_at(position, facing_of(ng)) : LeafGuide{};
}

class GuidedBsdf {
 public:
  /// `guide` nullptr (or α = 0): the BSDF alone. The guide's directions are world-space; the BSDF's local.
  GuidedBsdf(const Bsdf& bsdf, const Frame& frame, const VertexGuide* guide, float alpha)
      : bsdf_(bsdf), frame_(frame), guide_(alpha > 0.0f && guide && *guide ? guide : nullptr), alpha_(guide_ ? alpha : 0.0f) {}

  bool guided() const { return guide_ != nullptr; }
  /// A direction (local frame) with f and the mixture's per-lane density; u_lobe chooses guide or BSDF.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  /// The mixture's per-lane density of producing wi (local frame).
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;

 private:
  const Bsdf& bsdf_;
  const Frame& frame_;
  const VertexGuide* guide_;
  float alpha_;
};

}  // namespace rimu
