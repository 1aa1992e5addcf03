// Light a medium emits: the source term σ_a(x, λ)·L_e(x, λ) of the radiative transfer equation, L_e being the
// radiance an optically thick, non-scattering body of the medium would show (Kirchhoff: absorption and emission
// balance at equilibrium). Hot gas, fire, a glowing fog. Emission is not light-sampled (as in pbrt-v4): paths find
// it along their segments (emitted_along, spectral_distance_sampling.h).
#pragma once

#include <memory>

#include "spectral/spectra/spectrum.h"
#include "transport/media/grid_medium.h"

namespace rimu {

/// L_e(x, λ) of a medium: one spectrum everywhere, or a black body at the temperature of a grid.
class MediumEmission {
 public:
  /// The same radiance everywhere, scale × shape (film units: W/(m²·sr·nm)).
  MediumEmission(SpectrumPtr shape, double scale) : shape_(std::move(shape)), scale_(float(scale)) {}
  /// A black body at T(x) = (grid(x) − offset_k) × temperature_scale, its peak scaled to `scale` (pbrt-v4's
  /// temperature emission: L_e = scale · B(λ, T)/B(λ_max, T)); no emission where T ≤ 100 K, as in pbrt-v4. The grid's
  /// density() is read as the temperature (a GridMedium only for its lookup and placement).
  MediumEmission(std::shared_ptr<const GridMedium> temperature, double offset_k, double temperature_scale, double scale);

  /// True if L_e is the same everywhere (radiance_at then ignores the point).
  bool uniform() const { return shape_ != nullptr; }
  /// L_e at a world point.
  SampledSpectrum radiance_at(Vec3 p, const SampledWavelengths& lambda) const;

 private:
  SpectrumPtr shape_;  // uniform emission (null for a temperature grid)
  std::shared_ptr<const GridMedium> temperature_;
  float offset_k_ = 0, temperature_scale_ = 1, scale_ = 1;
};

}  // namespace rimu
