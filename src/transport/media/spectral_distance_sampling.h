// Free-flight distance sampling, transmittance and the light a medium emits along a segment, for four wavelengths at
// once (docs/media.md has the maths).
#pragma once

#include "transport/media/medium.h"
#include "transport/sampling/sampler.h"
#include "transport/sampling/walk_random.h"

namespace rimu {

/// How a path's four lanes share one free-flight decision.
enum class DistanceSampling {
  /// The hero's σ_t samples the distance (homogeneous: exactly; grids: null-scattering tracking with the hero's
  /// collision probabilities, Miller, Georgiev, Jarosz 2019); every lane is weighted by the balance heuristic over
  /// the four lanes' densities through the ratios R_k (Wilkie et al. 2014; Raab et al. 2008 §3.2).
  spectral_mis,
  /// The hero samples as above, the other lanes are divided by the hero's density alone (no spectral MIS): the
  /// pbrt-v4-style baseline. Unbiased only where the hero's density covers every lane's integrand.
  hero_only,
  /// One density for all lanes from the lanes' mean σ_t (homogeneous: exact; grids: null-collision tracking with
  /// collision probabilities from the lanes' mean coefficients). Lane-independent, so R_k is unchanged.
  averaged,
  /// Null-collision tracking for every medium, homogeneous ones included, with the history-aware collision
  /// probabilities of spectral tracking (Kutz, Habel, Li, Novák 2017, §5.2): P_s ∝ mean_k(σ_s,k·|β̂_k|),
  /// P_n ∝ mean_k(σ_n,k·|β̂_k|), β̂ the path's effective per-lane throughput. Lane-independent: R_k is unchanged.
  spectral_tracking,
};

/// The outcome of one free flight over [ray.t_min, t_max) inside one medium.
struct FreeFlight {
  bool scattered = false;  ///< a real scattering event at distance t (else the segment reached t_max)
  float t = 0;
  /// Multiplies the path throughput β: (contribution of the segment per lane) / (the technique's density as run).
  /// For a scattering event it includes σ_s at the event; not the phase function.
  SampledSpectrum weight = Float4(1.0f);
  /// Multiplies R_k: lane k's density of the same decisions relative to the density as run (1 where lanes share it).
  SampledSpectrum pdf_ratio = Float4(1.0f);
  /// When !scattered: the probability with which the technique as run passed the segment (the hero's, or the
  /// shared one). MIS against light sampling needs it: S_bsdf = q_dir · pass · Σ R_k (after the update).
  float pass_probability = 1;
  bool terminated() const { return max_lane(weight) <= 0.0f; }
};

/// Transmittance of a shadow-ray segment, and the densities with which free-flight sampling would have passed it.
struct SegmentTransmittance {
  SampledSpectrum transmittance = Float4(1.0f);  ///< exact (homogeneous, non-tracking modes) or a ratio-tracking estimate
  /// Lane k's probability that free-flight sampling (same mode, lane k as hero) passes this segment along the
  /// same null-collision vertices: S_bsdf for NEE's MIS weight is q_dir · Σ_k R_k · pass_probability_k.
  SampledSpectrum pass_probability = Float4(1.0f);
};

/// Whether free flights and transmittance in `medium` are tracked through null collisions (grid and noise-cloud media, or the
/// spectral_tracking mode): then they consume random numbers per tentative collision and read the throughput; else
/// they are analytic (homogeneous media) and read neither.
bool uses_tracking(const Medium& medium, DistanceSampling mode);

/// Samples a free flight from ray.origin along ray.direction (unit) until t_max (the next surface) in `medium`.
/// Consumes one sampler dimension either way: the analytic modes' exponential sample, or the trackers' first step
/// (their other numbers come from a WalkRandom keyed by it and the ray: sampling/walk_random.h says why).
/// `throughput` is the path's effective per-lane throughput (only spectral_tracking reads it; any positive
/// multiple will do); it is updated along the flight's null collisions for the next segment, as a multiple
/// rescaled so that its largest lane is 1.
FreeFlight sample_free_flight(const Medium& medium, const Ray& ray, float t_max, const SampledWavelengths& lambda,
                              DistanceSampling mode, Sampler& sampler, SampledSpectrum& throughput);

/// The transmittance over [ray.t_min, t_max): exp(−σ_t d) for homogeneous media (analytic modes), else ratio
/// tracking (Novák, Selle, Jarosz 2014) against the majorant grid, with Russian roulette once every lane's estimate
/// is below 0.1. Consumes no sampler dimension when analytic, one when tracked (the walk's first step; the rest
/// from a WalkRandom, as sample_free_flight).
/// `throughput` is what the free-flight technique's throughput would be on this segment (spectral_tracking's
/// probabilities depend on it, and so do the pass probabilities); updated along the null collisions (rescaled so
/// that its largest lane is 1: only its direction matters, and this keeps it finite).
SegmentTransmittance estimate_transmittance(const Medium& medium, const Ray& ray, float t_max,
                                            const SampledWavelengths& lambda, DistanceSampling mode, Sampler& sampler,
                                            SampledSpectrum& throughput);
/// The same with every number of a tracked walk from `random` (no sampler dimension; may be null when
/// !uses_tracking): a shadow ray keys one stream by its own ray for every medium it crosses, so that it takes no
/// sampler dimension, whatever it crosses.
SegmentTransmittance estimate_transmittance(const Medium& medium, const Ray& ray, float t_max,
                                            const SampledWavelengths& lambda, DistanceSampling mode,
                                            WalkRandom* random, SampledSpectrum& throughput);

/// An estimate of ∫ T(t)·σ_a(t)·L_e(t) dt over [ray.t_min, t_max) per lane: the light an emissive medium
/// (Medium::emission, non-null) adds along the segment, seen from ray.origin. Homogeneous media with uniform
/// emission: exact, σ_a L_e (1 − e^{−σ_t d}) / σ_t, no random numbers. Otherwise a collision estimator over the
/// majorant grid's tentative collisions (rate μ̄, the lanes' largest σ_t): Σ_i T̂_i σ_a L_e(t_i) / μ̄ with T̂ the
/// ratio-tracking transmittance up to t_i (Novák, Selle, Jarosz 2014), Russian roulette once every lane's T̂ is
/// below 0.1 (one sampler dimension when tracked, as estimate_transmittance). Unbiased in every lane whatever the
/// path's distance sampling: it is an estimator of its own, added to
/// the path's light as surface emission reached by the same segment would be.
SampledSpectrum emitted_along(const Medium& medium, const Ray& ray, float t_max, const SampledWavelengths& lambda,
                              Sampler& sampler);

}  // namespace rimu
