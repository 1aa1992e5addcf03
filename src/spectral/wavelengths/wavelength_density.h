// A scene's own wavelength sampling density: tabulated on 1 nm bins, drawn by an inverse CDF.
#pragma once

#include <functional>
#include <vector>

#include "spectral/colorimetry/observer.h"
#include "spectral/wavelengths/sampled_wavelengths.h"

namespace rimu {

/// A density over 360-830 nm, constant on each 1 nm bin [360 + i, 361 + i), i = 0 … 469.
///
/// What it is for: the visible density (sampled_wavelengths.h) follows the colour-matching functions and knows
/// nothing of the light. Under a line spectrum (fluorescent F11, many LEDs) most of its wavelengths land where the
/// light emits little, and the few that hit a line carry large weights: colour noise. A density built from the
/// scene's emission (light_weighted_wavelength_density) puts the wavelengths where the light is. The hero and its
/// partners are rotated in primary-sample space, λ_j = P⁻¹((u + j/4) mod 1), as for the visible density, so each
/// lane's marginal is this density and spectral MIS is unchanged (the density of the lane set is the same
/// whichever lane is the hero).
///
/// Piecewise constant at 1 nm is exact for what it must be, a positive density with an exact pdf: it need not
/// reproduce the light's shape finely, only keep the weights f/p bounded, which 1 nm bins do for tables at 1-10 nm.
class TabulatedWavelengthDensity {
 public:
  static constexpr int kBins = 470;

  /// From kBins non-negative, finite weights (at least one positive); normalised here. Cost: O(kBins).
  explicit TabulatedWavelengthDensity(const std::vector<double>& bin_weights);

  /// The density at λ, per nm (0 outside [360, 830)).
  float pdf(float lambda_nm) const;
  /// The inverse CDF: u ∈ [0, 1) → λ ∈ [360, 830) within a bin of positive weight. Cost: a guide-table lookup and
  /// a short scan (a few ns).
  float sample(float u) const;
  /// Hero + three partners rotated by quarters in primary-sample space, each with its pdf.
  SampledWavelengths sample_wavelengths(float u) const;

 private:
  std::vector<float> pdf_;    // kBins densities, 1/nm
  std::vector<double> cdf_;   // kBins + 1 values, cdf_[0] = 0, cdf_[kBins] = 1 (double: a float CDF near 1 has
                              // steps of 6e-8, coarse against the tails' 1e-4 per-nm densities)
  std::vector<int> guide_;    // kGuide + 1 entries: the bin holding u = k / kGuide
  static constexpr int kGuide = 512;
};

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
