// CIE daylight illuminants from a correlated colour temperature (CIE 15:2004 §3.1).
#pragma once

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

/// The daylight basis S0, S1, S2 (CIE 15:2004 Table T.2), as loaded from data/spectra/illuminants.
struct DaylightBasis {
  TabulatedSpectrum s0, s1, s2;
};

/// Chromaticity of CIE daylight at correlated colour temperature `cct_k` (CIE 15:2004 eqs. 3.3-3.4), valid
/// 4000-25000 K. Throws InputError outside that range.
Chromaticity daylight_chromaticity(double cct_k);

/// How M1, M2 are computed. CIE 15:2004 §3.1 rounds them to three decimals to reproduce the tabulated D
/// illuminants; Rimu keeps them unrounded for a CCT the user asks for.
enum class DaylightRounding { exact, cie_three_decimals };

/// The temperature a CIE D illuminant named after `nominal_k` is defined at (CIE 15:2004 §3.1): the names date
/// from c2 = 1.4380e-2 m·K; with today's 1.4388e-2 the same chromaticities lie at nominal × 1.4388/1.4380, e.g. D55
/// at 5503 K and D75 at 7504 K.
double cie_daylight_defined_cct_k(double nominal_k);

/// S(λ) = S0 + M1·S1 + M2·S2 at `cct_k` (relative power, ≈100 at 560 nm), sampled on the basis' 5 nm grid and
/// linearly interpolated between (CIE 15:2004 recommends linear interpolation of the basis).
TabulatedSpectrum daylight_spectrum(const DaylightBasis& basis, double cct_k,
                                    DaylightRounding rounding = DaylightRounding::exact);

}  // namespace rimu
