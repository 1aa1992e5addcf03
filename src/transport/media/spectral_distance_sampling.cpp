#include "transport/media/spectral_distance_sampling.h"

#include <cassert>
#include <cmath>

#include "transport/sampling/exponential_warp.h"
#include "transport/sampling/walk_random.h"

namespace rimu {
namespace {

float mean_lane(Float4 v) { return 0.25f * sum(v); }

// a / b per lane, 0 where b = 0 (a lane whose collision probabilities are undefined has density 0).
Float4 safe_divide(Float4 a, Float4 b) { return select(b > Float4(0.0f), a / b, Float4(0.0f)); }

// A free-flight distance with density σ exp(−σ t); infinite for σ = 0 (the flight never collides).
float exponential_distance(float sigma, float u) { return sigma > 0.0f ? sample_unit_exponential(u) / sigma : INFINITY; }

// Calls segment(t0, t1, majorant, coefficients_at) over the pieces of [t_min, t_max) with a constant majorant
// μ̄ (per metre, the same for every lane: the largest σ_t of any lane in the piece); coefficients_at(t) gives σ_a,
// σ_s at the ray's point t (a grid finds it in its own space, where the walk already is: no transform per lookup).
template <typename F>
void for_each_majorant(const Medium& medium, const Ray& ray, float t_max, const SampledWavelengths& lambda, F&& f) {
  if (const HomogeneousMedium* h = medium.homogeneous()) {
    const MediumCoefficients c = h->coefficients(lambda);
    f(ray.t_min, t_max, max_lane(c.sigma_t_per_m()), [c](float) { return c; });
    return;
  }
  if (const NoiseCloudMedium* cloud = medium.noise_cloud()) {
    // Density ≤ 1: σ_t per unit density bounds the whole box (one segment, as pbrt-v4's CloudMedium).
    const MediumCoefficients unit = cloud->unit_coefficients(lambda);
    float t0, t1;
    Ray local;
    if (!cloud->clip(ray, t_max, t0, t1, local)) return;
    f(t0, t1, max_lane(unit.sigma_t_per_m()),
      [&](float t) { return cloud->coefficients_in_medium(local.origin + local.direction * t, unit); });
    return;
  }
  const GridMedium& grid = *medium.grid();
  const MediumCoefficients unit = grid.unit_coefficients(lambda);
  const float unit_majorant = max_lane(unit.sigma_t_per_m());
  grid.for_each_majorant_segment(ray, t_max, [&](float t0, float t1, float max_density, const Ray& grid_ray) {
    return f(t0, t1, max_density * unit_majorant,
             [&](float t) { return grid.coefficients_in_grid(grid_ray.origin + grid_ray.direction * t, unit); });
  });
}

// Ratio tracking's Russian roulette threshold (estimate_transmittance).
constexpr float kTransmittanceRouletteBelow = 0.1f;

// Null-collision tracking's walk: calls collision(t, μ̄, coefficients, σ_n) at each tentative collision along
// [t_min, t_max), at exponential steps of rate μ̄, σ_n = max(μ̄ − σ_t, 0) per lane. collision returns false to
// end the walk. The steps' numbers come from `random` (walk_random.h), except the first, which is `first_u`: the
// sampler's one dimension for the walk, so that the first collision — the one a camera ray entering a medium
// makes — is stratified across a pixel's samples.
template <typename F>
void for_each_tentative_collision(const Medium& medium, const Ray& ray, float t_max, const SampledWavelengths& lambda,
                                  float first_u, WalkRandom& random, F&& collision) {
  bool first = true;
  for_each_majorant(medium, ray, t_max, lambda, [&](float t0, float t1, float majorant, auto&& coefficients_at) {
    if (!(majorant > 0.0f)) return true;
    for (float t = t0;;) {
      // Memorylessness: a step that leaves a piece is redrawn in the next one, so the first number may start any piece.
      t += exponential_distance(majorant, first ? first_u : random.next_1d());
      first = false;
      if (t >= t1) return true;
      const MediumCoefficients c = coefficients_at(t);
      const Float4 sigma_n = max(Float4(majorant) - c.sigma_t_per_m(), Float4(0.0f));
      if (!collision(t, majorant, c, sigma_n)) return false;
    }
  });
}

// The collision-type probabilities of a tracker at a tentative collision with coefficients σ_s, σ_n = μ̄ − σ_t:
// scatter with P_s, null with P_n = 1 − P_s (absorption is not sampled: it is left in the weights). Lane-wise
// versions (what P would have been with lane k as hero) are needed by spectral MIS.
struct CollisionProbabilities {
  float scatter = 0, null = 0;            // as run
  Float4 scatter_lane = Float4(1.0f), null_lane = Float4(1.0f);  // lane k as hero (spectral_mis), else = as run
};

CollisionProbabilities collision_probabilities(DistanceSampling mode, Float4 sigma_s, Float4 sigma_n,
                                               Float4 throughput) {
  CollisionProbabilities p;
  if (mode == DistanceSampling::spectral_mis || mode == DistanceSampling::hero_only) {
    const Float4 total = sigma_s + sigma_n;
    const Float4 ps = safe_divide(sigma_s, total), pn = safe_divide(sigma_n, total);
    p.scatter = ps[0];
    p.null = pn[0];
    if (mode == DistanceSampling::spectral_mis) {
      p.scatter_lane = ps;
      p.null_lane = pn;
    } else {
      p.scatter_lane = Float4(p.scatter);
      p.null_lane = Float4(p.null);
    }
    return p;
  }
  // averaged: the lanes' mean coefficients; spectral_tracking: weighted by the throughput (history-aware).
  Float4 w = Float4(1.0f);
  if (mode == DistanceSampling::spectral_tracking) {
    w = abs(throughput);  // scale-free: normalised so that large or tiny throughputs cannot overflow the means
    const float largest = max_lane(w);
    if (largest > 0.0f && std::isfinite(largest)) w = w / Float4(largest);
  }
  const float s = mean_lane(sigma_s * w), n = mean_lane(sigma_n * w);
  p.scatter = s + n > 0.0f ? s / (s + n) : 0.0f;
  p.null = s + n > 0.0f ? n / (s + n) : 0.0f;
  p.scatter_lane = Float4(p.scatter);
  p.null_lane = Float4(p.null);
  return p;
}

// The spectral-tracking weights after a null collision: throughput ⊙ σ_n, rescaled so that its largest lane is 1.
// The collision probabilities are ratios of weighted means, so any positive multiple gives the same ones; dropping
// the common factor 1/(μ̄ P_n) matters: in ratio tracking it is applied at every tentative collision, not only at
// sampled ones, and a lane carrying ~1e-40 of the throughput (σ_s = 1e-9 after a few scattering events) makes P_n
// denormal, 1/P_n overflow to inf and the next probabilities inf/inf = NaN (the non-finite samples of the
// σ_t ≈ 0-next-to-10 case). Lanes below ~1e-38 of the largest flush to 0: their expected share of the estimate
// is of that order.
Float4 tracking_weights_after_null(Float4 throughput, Float4 sigma_n) {
  const Float4 w = abs(throughput * sigma_n);
  const float largest = max_lane(w);
  return largest > 0.0f && std::isfinite(largest) ? w / Float4(largest) : w;
}


// Homogeneous media, analytic: one exponential distance from the hero's σ_t or the lanes' mean.
FreeFlight homogeneous_free_flight(const HomogeneousMedium& medium, const Ray& ray, float t_max,
                                   const SampledWavelengths& lambda, DistanceSampling mode, Sampler& sampler) {
  const MediumCoefficients c = medium.coefficients(lambda);
  const Float4 sigma_t = c.sigma_t_per_m();
  const float sigma_run = mode == DistanceSampling::averaged ? mean_lane(sigma_t) : sigma_t[0];
  const bool lane_ratios = mode == DistanceSampling::spectral_mis;
  const float t = ray.t_min + exponential_distance(sigma_run, sampler.next_1d());
  FreeFlight flight;
  if (t < t_max) {
    // Lane j: T_j(t) σ_s,j / (σ_run e^{−σ_run t}) = σ_s,j e^{−(σ_t,j − σ_run) t} / σ_run. The exponent's argument is
    // bounded by σ_run·t ≤ −log(1−u) (< 17 in float), so nothing overflows however far apart the lanes are.
    const float s = t - ray.t_min;
    const Float4 relative = exp(-(sigma_t - Float4(sigma_run)) * Float4(s));
    flight.scattered = true;
    flight.t = t;
    flight.weight = c.sigma_s_per_m * relative / Float4(sigma_run);
    // p_k(t) / p_0(t) = (σ_t,k / σ_t,0) e^{−(σ_t,k − σ_t,0) t}.
    if (lane_ratios) flight.pdf_ratio = Float4(1.0f / sigma_run) * sigma_t * relative;
    return flight;
  }
  // Passed: T_j(d) / P_run(d) with P_run = e^{−σ_run d}; lane k passes with P_k = e^{−σ_t,k d}.
  const float d = t_max - ray.t_min;
  const Float4 relative = exp(-(sigma_t - Float4(sigma_run)) * Float4(d));
  flight.weight = relative;
  if (lane_ratios) flight.pdf_ratio = relative;
  flight.pass_probability = std::exp(-sigma_run * d);
  return flight;
}

}  // namespace

bool uses_tracking(const Medium& medium, DistanceSampling mode) {
  return medium.homogeneous() == nullptr || mode == DistanceSampling::spectral_tracking;
}

FreeFlight sample_free_flight(const Medium& medium, const Ray& ray, float t_max, const SampledWavelengths& lambda,
                              DistanceSampling mode, Sampler& sampler, SampledSpectrum& throughput) {
  if (!uses_tracking(medium, mode)) return homogeneous_free_flight(*medium.homogeneous(), ray, t_max, lambda, mode, sampler);

  // Null-collision tracking: tentative collisions at rate μ̄ (lane-independent); at each, scatter or null by
  // the probabilities above. Path contribution per lane: σ_s at the real vertex, σ_n at null vertices, e^{−μ̄ t}
  // along the way; the density as run: μ̄ e^{−μ̄ t} · P_s or P_n. The exponentials cancel (docs/media.md).
  FreeFlight flight;
  const float first_u = sampler.next_1d();
  WalkRandom random(first_u, ray, t_max);
  for_each_tentative_collision(medium, ray, t_max, lambda, first_u, random,
                               [&](float t, float majorant, const MediumCoefficients& c, Float4 sigma_n) {
    const CollisionProbabilities p = collision_probabilities(mode, c.sigma_s_per_m, sigma_n, throughput);
    const float u = random.next_1d();
    if (p.scatter + p.null <= 0.0f) {  // the hero (or the mean) only absorbs here: the path ends
      flight.weight = Float4(0.0f);
      return false;
    }
    if (u < p.scatter) {
      flight.weight *= c.sigma_s_per_m / Float4(majorant * p.scatter);
      flight.pdf_ratio *= p.scatter_lane / Float4(p.scatter);
      flight.scattered = true;
      flight.t = t;
      return false;
    }
    const Float4 null_weight = sigma_n / Float4(majorant * p.null);
    flight.weight *= null_weight;
    throughput = tracking_weights_after_null(throughput, sigma_n);
    flight.pdf_ratio *= p.null_lane / Float4(p.null);
    flight.pass_probability *= p.null;
    return true;
  });
  return flight;
}

SegmentTransmittance estimate_transmittance(const Medium& medium, const Ray& ray, float t_max,
                                            const SampledWavelengths& lambda, DistanceSampling mode, Sampler& sampler,
                                            SampledSpectrum& throughput) {
  if (!uses_tracking(medium, mode)) return estimate_transmittance(medium, ray, t_max, lambda, mode, nullptr, throughput);
  WalkRandom random(sampler.next_1d(), ray, t_max);
  return estimate_transmittance(medium, ray, t_max, lambda, mode, &random, throughput);
}

SegmentTransmittance estimate_transmittance(const Medium& medium, const Ray& ray, float t_max,
                                            const SampledWavelengths& lambda, DistanceSampling mode,
                                            WalkRandom* random, SampledSpectrum& throughput) {
  SegmentTransmittance out;
  if (!uses_tracking(medium, mode)) {
    const MediumCoefficients c = medium.homogeneous()->coefficients(lambda);
    const Float4 sigma_t = c.sigma_t_per_m();
    const float d = t_max - ray.t_min;
    out.transmittance = exp(-sigma_t * Float4(d));
    if (mode == DistanceSampling::spectral_mis) out.pass_probability = out.transmittance;
    else if (mode == DistanceSampling::hero_only) out.pass_probability = Float4(std::exp(-sigma_t[0] * d));
    else out.pass_probability = Float4(std::exp(-mean_lane(sigma_t) * d));
    return out;
  }
  // Ratio tracking: T ≈ Π σ_n/μ̄ over tentative collisions at rate μ̄ (unbiased, bounded by 1 per step), with
  // Russian roulette once every lane's estimate is below kTransmittanceRouletteBelow: the walk continues with
  // probability T̂_max / threshold and its estimate is divided by that (so a survivor carries the threshold again).
  // Unbiased; without it a shadow ray from deep inside a dense grid walked every tentative collision to the far
  // side (hundreds of lookups) to return a transmittance of 10⁻¹⁰ — pbrt-v4 plays the same roulette below 0.05.
  // The pass probabilities of a walk that the roulette ends are never read: its transmittance is 0.
  assert(random);
  for_each_tentative_collision(medium, ray, t_max, lambda, random->next_1d(), *random,
                               [&](float, float majorant, const MediumCoefficients& c, Float4 sigma_n) {
    out.transmittance *= sigma_n / Float4(majorant);
    const CollisionProbabilities p = collision_probabilities(mode, c.sigma_s_per_m, sigma_n, throughput);
    out.pass_probability *= p.null_lane;
    // The free-flight technique would have carried this throughput through the same null collision.
    throughput = tracking_weights_after_null(throughput, sigma_n);
    const float largest = max_lane(out.transmittance);
    if (!(largest > 0.0f)) return false;  // stop once no lane passes
    if (largest < kTransmittanceRouletteBelow) {
      const float survive = largest / kTransmittanceRouletteBelow;
      if (random->next_1d() >= survive) {
        out.transmittance = Float4(0.0f);
        return false;
      }
      out.transmittance *= Float4(1.0f / survive);
    }
    return true;
  });
  return out;
}

SampledSpectrum emitted_along(const Medium& medium, const Ray& ray, float t_max, const SampledWavelengths& lambda,
                              Sampler& sampler) {
  const MediumEmission& emission = *medium.emission();
  const HomogeneousMedium* h = medium.homogeneous();
  if (h && emission.uniform()) {
    const MediumCoefficients c = h->coefficients(lambda);
    const Float4 sigma_t = c.sigma_t_per_m();
    const float d = std::fmin(t_max, 1e30f) - ray.t_min;
    if (!(d > 0.0f)) return Float4(0.0f);
    // (1 − e^{−σ_t d}) / σ_t, and its limit d where σ_t = 0 (then σ_a = 0 and the lane emits nothing anyway).
    const Float4 path_length = select(sigma_t > Float4(0.0f), (Float4(1.0f) - exp(-sigma_t * Float4(d))) / sigma_t, Float4(d));
    return c.sigma_a_per_m * emission.radiance_at(ray.origin, lambda) * path_length;
  }
  constexpr float kRouletteBelow = 0.1f;
  const std::optional<SampledSpectrum> uniform =
      emission.uniform() ? std::optional<SampledSpectrum>(emission.radiance_at(ray.origin, lambda)) : std::nullopt;
  SampledSpectrum sum_emitted(0.0f), transmittance(1.0f);
  const float first_u = sampler.next_1d();
  WalkRandom random(first_u, ray, t_max);
  for_each_tentative_collision(medium, ray, t_max, lambda, first_u, random,
                               [&](float t, float majorant, const MediumCoefficients& c, Float4 sigma_n) {
                                 if (max_lane(c.sigma_a_per_m) > 0.0f) {
                                   const SampledSpectrum le =
                                       uniform ? *uniform : emission.radiance_at(ray.origin + ray.direction * t, lambda);
                                   sum_emitted += transmittance * c.sigma_a_per_m * le * Float4(1.0f / majorant);
                                 }
                                 transmittance *= sigma_n * Float4(1.0f / majorant);
                                 const float largest = max_lane(transmittance);
                                 if (!(largest > 0.0f)) return false;
                                 if (largest < kRouletteBelow) {
                                   const float survive = largest / kRouletteBelow;
                                   if (random.next_1d() >= survive) return false;
                                   transmittance *= Float4(1.0f / survive);
                                 }
                                 return true;
                               });
  return sum_emitted;
}

}  // namespace rimu
