// The two weighted CIELAB colour differences between CIE76 and CIEDE2000: CIE94 and CMC(l:c). Both are
// asymmetric: the first colour is the reference (standard), whose chroma and hue set the weights.
#pragma once

#include "spectral/colorimetry/cielab.h"

namespace rimu {

/// CIE 116-1995's parametric factors and weighting constants for ΔE*94.
struct Cie94Factors {
  double k_l = 1, k_c = 1, k_h = 1;
  double k1 = 0.045, k2 = 0.015;  ///< S_C = 1 + k1·C*_ref, S_H = 1 + k2·C*_ref
  /// The graphic-arts set (CIE 116-1995): kL = 1, K1 = 0.045, K2 = 0.015.
  static Cie94Factors graphic_arts() { return {}; }
  /// The textiles set: kL = 2, K1 = 0.048, K2 = 0.014.
  static Cie94Factors textiles() { return {2, 1, 1, 0.048, 0.014}; }
};

/// CIE 1994 ΔE*94 (CIE 116-1995) of `sample` against `reference`. ΔH*² = Δa*² + Δb*² − ΔC*², held at 0 where
/// rounding makes it negative.
double delta_e_1994(const Lab& reference, const Lab& sample, const Cie94Factors& factors = {});

/// CMC(l:c) (Clarke, McDonald & Rigg 1984; BS 6923, ISO 105-J03) of `sample` against `reference`: l = 2, c = 1 for
/// acceptability, l = c = 1 for perceptibility.
double delta_e_cmc(const Lab& reference, const Lab& sample, double l = 2.0, double c = 1.0);

}  // namespace rimu
