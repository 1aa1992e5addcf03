// Chooses a whole light with probability proportional to its radiant power, whatever the shading point (part −1:
// an emissive mesh then picks its triangle by area inside Light::sample_li, jointly with the point).
//
// Why radiometric power (∫Φ_λ dλ over 360-830 nm, W) and not luminous power (lm): the film does not only record
// luminance. Z (z̄ peaks at 445 nm, where V(λ) is 0.04) and camera-RGB blue channels respond strongly where V is
// small, so picking by lumens would starve a blue or violet light of samples and leave blue noise; radiant power
// over the transported range treats every wavelength the film can record alike. It also needs no observer, so
// transport does not depend on the spectral library's tables. Lights at infinity are counted through a scene
// radius (Light::total_power_w), which is what makes this sampler fail in large scenes: an environment's weight
// grows with the radius squared and starves every local light (bvh_light_sampler.h does not).
#pragma once

#include <optional>
#include <span>

#include "transport/sampling/distribution_1d.h"
#include "transport/lights/light_sampler.h"

namespace rimu {

class PowerLightSampler final : public LightSampler {
 public:
  /// From each light's weight; every light is one part. Weights must be finite and ≥ 0 (asserted); zero-weight
  /// lights are never picked.
  explicit PowerLightSampler(std::span<const double> power_w);
  /// The weights are lights[i]->total_power_w(scene radius).
  PowerLightSampler(std::span<const Light* const> lights, double scene_radius_m);
  /// Every light with power gets the same probability: the uniform sampler.
  static PowerLightSampler uniform_over_lights(std::span<const Light* const> lights, double scene_radius_m);

  std::optional<LightChoice> sample(const LightSamplingPoint& at, float u) const override;
  /// P(light) for part −1; 0 for any other part (this sampler never returns one).
  float pmf(const LightSamplingPoint& at, int light, int part) const override;
  bool chooses_parts() const override { return false; }

  struct Pick {
    int index = 0;          ///< index into the weights / lights given at construction
    float probability = 0;  ///< > 0
  };
  /// A light with probability ∝ its weight, from u in [0, 1); std::nullopt if no light has power. O(log n).
  std::optional<Pick> pick(float u) const;
  /// The probability that pick() returns light `index` (0 for zero-power lights, bad indices, empty scenes).
  float probability(int index) const { return distribution_.probability(index); }
  /// Number of lights (including zero-power ones).
  int light_count() const { return distribution_.size(); }

 private:
  Distribution1D distribution_;
};

}  // namespace rimu
