// Equiangular sampling of a point along a ray towards a point light (Kulla & Fajardo 2012), and the densities that
// combine it with spectral free-flight sampling by MIS inside homogeneous media (docs/media.md).
#pragma once

#include <optional>

#include "transport/media/homogeneous_medium.h"
#include "transport/media/spectral_distance_sampling.h"

namespace rimu {

/// The ray segment o + t·d, t ∈ [t0, t1], seen from a light at `light_m` (a point light, or the centre the
/// technique aims at for a light with extent): Δ = (light − o)·d is the foot of the
/// perpendicular from the light, h its distance to the line.
struct EquiangularSegment {
  Vec3 origin, direction;  ///< direction: unit
  float t0 = 0, t1 = 0;    ///< t1 may be large (1e30) for a segment that leaves the scene
  Vec3 light_m;
  float time = 0;  ///< the path's moment in the shutter (Ray::time): where moving objects block the light

  /// Equiangular parameterisation (Kulla & Fajardo 2012, "Importance Sampling Techniques for Path Tracing in
  /// Participating Media", Computer Graphics Forum 31(4), EGSR; its point-light section): with θ(t) = atan((t − Δ)/h), t = Δ + h·tan(θ) for θ uniform in
  /// [θ(t0), θ(t1)], so the density is p(t) = h / ((θ1 − θ0)(h² + (t − Δ)²)) per metre: proportional to the 1/r²
  /// of a point light, which free-flight sampling (∝ e^{−σt}) ignores.
  struct Sample {
    float t = 0;
    float pdf_per_m = 0;
  };
  /// std::nullopt when the light is on the ray's line (h = 0: the 1/r² is not integrable there) or the segment
  /// is empty. Consumes one uniform number.
  std::optional<Sample> sample(float u) const;
  /// The density of sample() at t (0 outside [t0, t1] or when sample() would fail).
  float pdf(float t) const;

 private:
  struct Frame {
    float delta, h, theta0, theta1;
  };
  std::optional<Frame> frame() const;
};

/// Σ_k R_k · p_k(t): the density with which sample_free_flight (this mode, lane k as hero) scatters at distance
/// s = t − t0 of a homogeneous segment, weighted by the path's spectral-MIS ratios R_k before the flight.
/// spectral_mis: p_k = σ_t,k e^{−σ_t,k s}; hero_only: the hero's density for every k; averaged: σ̄ e^{−σ̄ s}.
/// (spectral_tracking and grids are not combined with equiangular sampling: their densities are not analytic.)
/// This is the distance technique's term in the balance heuristic of the combined estimator (docs/media.md).
float distance_technique_density(const MediumCoefficients& c, DistanceSampling mode, float s_m,
                                 const SampledSpectrum& ratios);

}  // namespace rimu
