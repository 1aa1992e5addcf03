// The smoothest non-negative knot spectrum with a given colour: the optimisation behind the upsampling table.
#pragma once

#include <optional>

#include "spectral/upsampling/upsampling_knots.h"

namespace rimu {

/// Smoothness of a knot spectrum: Σ_i (S_{i+1} − S_i)², the squared first differences (Meng et al. 2015, Eq. 4
/// measures smoothness the same way, on their own grid).
double roughness(const KnotValues& knots);

/// Result of smoothest_knot_spectrum.
struct SmoothestSpectrum {
  KnotValues knots{};
  int iterations = 0;  ///< active-set iterations used
};

/// Minimises roughness(S) subject to colorimetry.xyz_of(S) = target and S ≥ 0: a convex quadratic programme with
/// 95 unknowns, 3 equality constraints and 95 bounds, solved by an active-set method (the bound set is the
/// active set; each step solves the equality-constrained KKT system on the free knots). The result satisfies the
/// KKT conditions to 1e-10. Returns nullopt if `target` lies outside the knot gamut (no non-negative solution)
/// or the iteration does not settle. Costs ~0.1-2 ms; for the offline table, not for rendering.
std::optional<SmoothestSpectrum> smoothest_knot_spectrum(const KnotColorimetry& colorimetry, const Xyz& target);

}  // namespace rimu
