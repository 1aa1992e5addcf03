// A scene's own wavelength sampling density: tabulated on 1 nm bins, drawn by an inverse CDF.
#pragma once

#include <vector>

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

}  // namespace rimu
