// Where a camera sample's radiance goes when the scene splits its lights into groups (light groups: the beauty as
// a sum of one image per group, rebalanced after the render by `rimu display --group`).
#pragma once

#include "spectral/wavelengths/sampled_wavelengths.h"

namespace rimu {

/// The per-group share of one camera sample's radiance. Every emitted-radiance contribution the integrator adds to
/// its result (next-event estimation, lights hit by BSDF or phase sampling, rays escaping to lights at infinity,
/// equiangular connections in media), with the same MIS weight, is also added to the slot of the emitting light's
/// group (Light::light_group()). Contributions are never negative, so the slots sum to the result up to float
/// rounding. `groups == nullptr` (a scene without groups) costs one predictable branch per contribution.
struct LightGroupRadiance {
  SampledSpectrum* groups = nullptr;  ///< `count` slots, zeroed by the caller before each camera sample
  int count = 0;

  void add(int group, const SampledSpectrum& contribution) const {
    if (groups) groups[group] += contribution;
  }
  /// Multiplies every slot by `mask` (single-wavelength mode keeps the hero lane only, as the result does).
  void mask(const SampledSpectrum& mask) const {
    for (int g = 0; g < count; ++g) groups[g] *= mask;
  }
};

}  // namespace rimu
