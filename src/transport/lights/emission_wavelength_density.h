// The wavelength density of a scene's lights: where in the spectrum its emitted power is.
#pragma once

#include <memory>
#include <vector>

#include "spectral/colorimetry/observer.h"
#include "spectral/wavelengths/wavelength_density.h"
#include "transport/lights/light.h"
#include "transport/lights/power_light_sampler.h"

namespace rimu {

/// The share of the visible density kept by emission_wavelength_density: every lane's weight f/p is then at most
/// 1/0.25 = 4 times what it would be under the visible density alone (docs/sampling.md, "Wavelength density").
inline constexpr double kEmissionDensityDefensiveFraction = 0.25;

/// light_weighted_wavelength_density with S(λ) = Σᵢ Pᵢ sᵢ(λ)/∫sᵢ dλ: each light's emitted spectrum shape
/// (Light::emitted_spectrum), normalised, weighted by its probability Pᵢ under the power sampler (∝ its radiant
/// power, whichever sampler next-event estimation uses: a spatial sampler has no one probability per light). A
/// light without one shape (an environment image) contributes Pᵢ as a flat spectrum, i.e. the visible density. Cost: one 1 nm integral per light plus 1880 evaluations of S.
/// `response`: the three channel curves the density balances (the loader passes CIE 1931 x̄, ȳ, z̄).
TabulatedWavelengthDensity emission_wavelength_density(const std::vector<std::unique_ptr<Light>>& lights,
                                                       const PowerLightSampler& light_sampler, const Observer& response,
                                                       double defensive_fraction = kEmissionDensityDefensiveFraction);

}  // namespace rimu
