// Chooses which light next-event estimation samples: with probability proportional to its radiant power.
//
// Why radiometric power (∫Φ_λ dλ over 360-830 nm, W) and not luminous power (lm): the film does not only record
// luminance. Z (z̄ peaks at 445 nm, where V(λ) is 0.04) and camera-RGB blue channels respond strongly where V is
// small, so picking by lumens would starve a blue or violet light of samples and leave blue noise; radiant power
// over the transported range treats every wavelength the film can record alike. It also needs no observer, so
// transport does not depend on the spectral library's tables. Lights at infinity are counted through a scene
// radius (Light::total_power_w). The choice only moves variance: any probability that is positive wherever a
// light can contribute gives an unbiased estimate.
#pragma once

#include <optional>
#include <span>

#include "transport/distribution_1d.h"

namespace rimu {

class Light;

class LightSampler {
 public:
  /// From each light's weight, normally total_power_w(scene radius). Weights must be finite and ≥ 0 (asserted);
  /// zero-weight lights are never picked.
  explicit LightSampler(std::span<const double> power_w);
  /// Convenience: the weights are lights[i]->total_power_w(scene_radius_m).
  LightSampler(std::span<const Light* const> lights, double scene_radius_m);

  struct Pick {
    int index = 0;          ///< index into the weights / lights given at construction
    float probability = 0;  ///< > 0
  };
  /// A light with probability ∝ its power, from u in [0, 1); std::nullopt if no light has power. O(log n).
  std::optional<Pick> pick(float u) const;
  /// The probability that pick() returns light `index` (0 for zero-power lights, bad indices, empty scenes).
  float probability(int index) const { return distribution_.probability(index); }
  /// Number of lights (including zero-power ones).
  int light_count() const { return distribution_.size(); }

 private:
  Distribution1D distribution_;
};

}  // namespace rimu
