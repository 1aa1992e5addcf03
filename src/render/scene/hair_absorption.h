// Hair absorption from melanin concentrations, as pbrt-v4 computes it, for the scene format's "hair" material.
#pragma once

#include "spectral/library/spectral_library.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

/// σa(λ) per unit fibre radius of a fibre with `eumelanin` and `pheomelanin` concentrations (≥ 0): pbrt-v4's
/// RGB absorption per unit concentration, eumelanin (0.419, 0.697, 1.37) and pheomelanin (0.187, 0.4, 1.05)
/// (pbrt-v3 §9.9.6, after d'Eon et al. 2011), summed in linear sRGB and turned into a spectrum the way pbrt-v4
/// does, its RGBUnboundedSpectrum (the sigmoid fit of rgb/(2·max), times 2·max: SigmoidFitter::fit_unbounded),
/// tabulated at 1 nm over 360-830 nm. ~1 ms (one fit). Both 0 gives σa = 0 (a white fibre).
SpectrumPtr melanin_sigma_a(SpectralLibrary& library, double eumelanin, double pheomelanin);

}  // namespace rimu
