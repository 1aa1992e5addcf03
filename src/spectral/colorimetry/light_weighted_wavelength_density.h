// The wavelength density that follows a scene's emission through an observer's channels (the "lights" density of
// spectral/wavelengths/wavelength_density.h, built from the scene by transport/lights/emission_wavelength_density.h).
#pragma once

#include <functional>

#include "spectral/colorimetry/observer.h"
#include "spectral/wavelengths/wavelength_density.h"

namespace rimu {

/// A density that follows the emitted spectrum S through each channel of `response`, mixed with the visible one:
///   p(λ) = (1 − m) · S(λ) Σ_c r_c(λ)/W_c / 3  +  m · p_vis(λ),   W_c = ∫ S r_c dλ,   m = `defensive_fraction` ∈ (0, 1].
/// Each channel c gets a third of the emission part, distributed like its own integrand S·r_c: what minimises the
/// channels' relative variances together for light that reaches the film with the emitted spectrum. Under a warm
/// light (CIE A) Z's integrand is small and blue; S·(x̄ + ȳ + z̄) alone would starve it, while the per-channel
/// normalisation keeps it a third. A channel with W_c = 0 is left out. S is the scene's emitted spectral power (any
/// positive scale); `response` stands for the film (the loader passes CIE 1931 x̄, ȳ, z̄). The defensive part
/// (Hesterberg 1995) bounds every weight by 1/m times the visible density's, for light whose spectrum the emission
/// does not predict (a saturated reflectance, a camera film). Each bin's weight is the bin's mean at 0.25 nm steps.
TabulatedWavelengthDensity light_weighted_wavelength_density(const std::function<double(double)>& relative_power,
                                                             const Observer& response, double defensive_fraction);

}  // namespace rimu
