// The random numbers of a variable-length walk (a medium's null-collision tracking, the layered BSDF's walk between
// its interfaces): a PCG32 stream keyed by one sampler dimension and the walk's ray, or by a hash.
//
// Why not the sampler. A tracker draws one or two numbers per tentative collision, hundreds along a ray through a
// dense grid. Drawn from the path's sampler, (1) each is a low-discrepancy dimension that buys nothing — the k-th
// draw means a different decision in every sample, since the walks have different lengths — and costs a Sobol'
// draw beyond the sampler's cached dimensions, and (2) the walk's variable count shifts every later dimension of
// the path, so the phase function's and the lights' samples at the next vertex are no longer stratified across a
// pixel's samples either. With the walk on a stream of its own the path takes a fixed number of dimensions per
// vertex. (pbrt-v4 does the same: its majorant walks draw from an RNG hashed from the ray.)
//
// Determinism: the stream is a function of the sampler's value (seed, pixel, sample index, dimension) and of the
// ray, so an image still depends on nothing else (thread count, tile order).
#pragma once

#include <bit>
#include <cstdint>

#include "transport/geometry/ray.h"
#include "transport/sampling/bit_mixing.h"
#include "transport/sampling/pcg32.h"

namespace rimu {

class WalkRandom {
 public:
  /// A stream keyed by a hash (the layered BSDF keys its walks by the directions it evaluates).
  explicit WalkRandom(uint64_t key) { seed(mix_bits(key)); }
  /// A stream keyed by the ray alone, for a walk along a ray the sampler has already placed (a shadow ray towards a
  /// sampled point of a light, from a vertex the path's numbers chose): it costs the path no dimension, so a shadow
  /// ray takes none whether or not it crosses a medium, as in scenes without media.
  WalkRandom(const Ray& ray, float t_max) : WalkRandom(0.5f, ray, t_max) {}
  /// A stream keyed by one uniform number from the path's sampler (`u`, in [0, 1)) and the walk's ray and end:
  /// two walks with the same u (24-bit values repeat after 2²⁴ draws) but different rays get unrelated streams.
  WalkRandom(float u, const Ray& ray, float t_max) {
    // A multiply-add chain over the words (cheap: a walk may be short), then two full mixes.
    uint64_t key = std::bit_cast<uint32_t>(u);
    for (float f : {ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y, ray.direction.z,
                    ray.t_min, t_max})
      key = key * 0x9e3779b97f4a7c15ULL + std::bit_cast<uint32_t>(f);
    seed(mix_bits(key));
  }

  /// Uniform in [0, 1): 24 random bits, exactly representable in float, never 1 (as the samplers' numbers).
  float next_1d() { return random_.next_1d(); }
  Vec2 next_2d() {
    const float a = next_1d();
    return {a, next_1d()};
  }

 private:
  void seed(uint64_t key) {
    random_.increment = (key << 1) | 1u;  // odd: the stream
    random_.state = mix_bits(key + random_.increment);
  }
  Pcg32 random_;
};

}  // namespace rimu
