// A parallax-aware mixture of von Mises–Fisher lobes: the directional part of the guiding field in the manner of
// Ruppert, Herholz & Lensch, "Robust Fitting of Parallax-Aware Mixtures for Path Guiding" (SIGGRAPH 2020).
//
// Why lobes and not the quadtree alone: a spatial leaf ~1 m wide sees a sun patch on the floor in directions tens
// of degrees apart from its two ends, so a distribution learned for the whole leaf is blurred by that parallax
// (docs/benchmarks.md, "Path guiding", third round: ~5× on the daylit room's ceiling). Each lobe here also learns
// how far away its light is; at a vertex the lobe is re-aimed from the leaf's pivot to that vertex, which keeps it
// on the patch. A re-aimed vMF lobe is still a normalised vMF lobe, so the density stays exact.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "transport/geometry/vector.h"
#include "transport/guiding/guiding_sample.h"

namespace rimu {

struct VmfLobe {
  Vec3 mean;                 ///< unit mean direction as seen from the pivot
  float kappa = 0.0f;        ///< concentration (0: uniform over the sphere)
  float weight = 0.0f;       ///< mixture weight; the lobes' sum to 1
  float inverse_distance = 0.0f;  ///< 1 / (harmonic mean distance of its light from the pivot); 0: at infinity
  float normalisation = 0.0f;     ///< vmf_normalisation(kappa), kept for VmfMixture::at
};

struct VmfMixtureSettings {
  int lobes = 8;
  int iterations = 16;
  int max_fit_samples = 8192;  ///< a leaf fits to at most this many of its weighted samples (a fixed stride)
  float max_kappa = 2000.0f;   ///< ~1.3° wide: narrower lobes would follow single lucky samples
  /// The prior on each lobe's concentration: κ is shrunk by n/(n + prior) with n the lobe's effective sample count
  /// ((Σw)²/Σw² of its share of the samples), so a lobe resting on a few heavy samples stays wide.
  float concentration_prior = 8.0f;
  bool background_component = true;  ///< fit with a uniform component, dropped afterwards (vmf_mixture.cpp)
};

/// The lobes as seen from one vertex (re-aimed for parallax): the distribution a guided vertex samples.
class VertexMixture {
 public:
  static constexpr int kMaxLobes = 16;
  int count = 0;
  std::array<Vec3, kMaxLobes> mean{};
  std::array<float, kMaxLobes> kappa{};
  std::array<float, kMaxLobes> weight{};
  std::array<float, kMaxLobes> normalisation{};  ///< κ / (2π (1 − e^{−2κ})), or 1/(4π) for κ = 0

  /// A direction drawn from the mixture: u_lobe ∈ [0, 1) picks the lobe, u the direction in it.
  Vec3 sample(float u_lobe, Vec2 u) const;
  float pdf(Vec3 direction) const;
};

class VmfMixture {
 public:
  /// Fits the mixture to `samples` (weights ≥ 0; a leaf's records, read where they are: only the ones the fit keeps,
  /// at most max_fit_samples, are copied, as seen from the pivot). Empty when their weights sum to zero.
  static VmfMixture fit(std::span<const GuidingSample> samples, const VmfMixtureSettings& settings);

  bool empty() const { return lobes_.empty(); }
  float effective_samples() const { return effective_samples_; }
  /// The mixture seen from `position`: every lobe with a finite distance re-aimed at its light.
  VertexMixture at(Vec3 position) const;

  const std::vector<VmfLobe>& lobes() const { return lobes_; }
  Vec3 pivot() const { return pivot_; }
  size_t memory_bytes() const { return lobes_.capacity() * sizeof(VmfLobe); }

 private:
  std::vector<VmfLobe> lobes_;
  Vec3 pivot_{0, 0, 0};
  float effective_samples_ = 0.0f;
};

/// The density of a vMF lobe of concentration κ at cosine c to its mean, and a sample of that cosine; numerically
/// stable for κ → 0 and large κ (W. Jakob, "Numerically stable sampling of the von Mises Fisher distribution on
/// S² (and other tricks)", 2012).
float vmf_normalisation(float kappa);
float sample_vmf_cosine(float kappa, float u);

}  // namespace rimu
