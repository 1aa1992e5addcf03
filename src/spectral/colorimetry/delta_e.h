// Colour differences between two CIELAB colours: CIE76 ΔE*ab and CIEDE2000 ΔE00.
#pragma once

#include "spectral/colorimetry/cielab.h"

namespace rimu {

/// CIE 1976 ΔE*ab: the Euclidean distance in CIELAB (CIE 15:2004 section 8.2.1).
double delta_e_1976(const Lab& first, const Lab& second);

/// CIEDE2000's parametric factors kL, kC, kH (all 1 under the reference conditions of CIE 142-2001;
/// textiles commonly use kL = 2).
struct Ciede2000Factors {
  double k_l = 1, k_c = 1, k_h = 1;
};

/// CIEDE2000 ΔE00 (CIE 142-2001), following Sharma, Wu & Dalal (2005), "The CIEDE2000 color-difference
/// formula: implementation notes, supplementary test data, and mathematical observations", Color Res. Appl.
/// 30(1):21-30. Symmetric in its two arguments.
double delta_e_2000(const Lab& first, const Lab& second, const Ciede2000Factors& factors = {});

}  // namespace rimu
