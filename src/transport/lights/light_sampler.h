// Chooses which light (and which part of it: a triangle of an emissive mesh) next-event estimation samples from a
// shading point. Four strategies share this interface (light_sampler.cpp builds them by kind):
//   bvh (the default; bvh_light_sampler.h): by an estimate of each light's contribution at the point;
//   bvh-spectral (the same tree): by that estimate at the path's four wavelengths (docs/sampling.md);
//   power (power_light_sampler.h): by radiant power, ignoring the point;
//   uniform: every light with power equally (for tests).
// Any choice that gives positive probability to every light that can contribute at the point is unbiased; the
// integrators divide by the probability sample() returns, and weight BSDF-sampled hits on a light with pmf().
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "transport/geometry/vector.h"

namespace rimu {

class Light;
class SampledWavelengths;

/// Where a light is being chosen for.
struct LightSamplingPoint {
  Vec3 position_m;
  /// The geometric normal of an opaque surface, on the side light may arrive from (the integrators drop light from
  /// below it); zero for a point in a medium or on a surface that transmits, where light from every direction counts.
  Vec3 normal;
  /// The path's wavelengths, for samplers that choose by power at them (bvh-spectral); nullptr: by power over
  /// 360-830 nm. sample() and pmf() must be given the same wavelengths for the same path (the integrators pass
  /// the path's own, which do not change along it). The sampler reads them only during the call.
  const SampledWavelengths* wavelengths = nullptr;
};

struct LightChoice {
  int light = 0;  ///< index into the lights given at construction
  /// The part (Light::part_count(): the triangle of an emissive mesh, else 0) for samplers that choose parts;
  /// −1 for samplers that choose whole lights (Light::sample_part_li/pdf_part_li then sample the whole light).
  int part = 0;
  float probability = 0;  ///< > 0: the probability of this (light, part) at the point
};

class LightSampler {
 public:
  virtual ~LightSampler() = default;
  /// A (light, part) from u in [0, 1), with its probability; std::nullopt if no light can contribute at `at` (or,
  /// for the BVH, the descent met only clusters that cannot). The probabilities of one point sum to at most 1.
  virtual std::optional<LightChoice> sample(const LightSamplingPoint& at, float u) const = 0;
  /// Exactly the probability sample(at, ·) returns for (light, part); 0 if it never returns it.
  virtual float pmf(const LightSamplingPoint& at, int light, int part) const = 0;
  /// True if sample() chooses parts (the BVH: each triangle its own leaf); false if it chooses whole lights and
  /// returns part −1 (power, uniform: the light then picks its triangle by area jointly with the point, which keeps
  /// the point's 2D stratification over the whole mesh).
  virtual bool chooses_parts() const = 0;
  /// The part index this sampler uses for a hit on triangle `primitive` of a light (0 for lights of one part, e.g.
  /// at infinity): the primitive, or −1 for samplers of whole lights.
  int part_of_hit(uint32_t primitive) const { return chooses_parts() ? int(primitive) : -1; }
};

enum class LightSamplerKind { bvh, bvh_spectral, power, uniform };

/// "bvh", "bvh-spectral", "power", "uniform"; std::nullopt for anything else.
std::optional<LightSamplerKind> parse_light_sampler_kind(std::string_view name);
const char* light_sampler_kind_name(LightSamplerKind kind);

/// The sampler of `kind` over `lights` (which must outlive it). `scene_radius_m` only matters to the power
/// sampler, which weighs lights at infinity by the power they send through a sphere of that radius.
std::unique_ptr<LightSampler> make_light_sampler(LightSamplerKind kind, std::span<const Light* const> lights,
                                                 double scene_radius_m);

}  // namespace rimu
