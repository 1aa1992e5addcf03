// The maximal-gamut figure (Manuka course notes Fig. 6, after Meng et al. 2015): brightest reflectance per
// chromaticity for MacAdam's optimal colours and for the upsampler's smooth spectra.
#pragma once

#include <filesystem>
#include <vector>

#include "spectral/upsampling/rgb_upsampler.h"

namespace rimu {

/// One xy bin of the figure. Brightness is X+Y+Z with the perfect white at Y = 1 (white X+Y+Z = 3.04 for D65).
struct GamutFigureBin {
  Chromaticity xy;              ///< bin centre
  double optimal_xyz_sum = -1;  ///< brightest optimal (block / complement-of-block) reflectance; −1 if none hit the bin
  double smooth_xyz_sum = -1;   ///< the upsampler's brightness limit there; −1 outside its gamut
};

/// Both limits on a grid of `bin_size` over x in [0, 0.75], y in [0, 0.85], under `upsampler`'s white.
/// MacAdam (1935): the brightest reflectance of a chromaticity is 1 on one wavelength band and 0 elsewhere, or
/// the complement; every band [λ1, λ2] with edges on a 0.2 nm grid over 360-830 nm, and its complement, is
/// evaluated and the maximum X+Y+Z kept per bin. Cost: ~3 s.
std::vector<GamutFigureBin> gamut_figure_bins(SpectralLibrary& library, const RgbUpsampler& upsampler,
                                              double bin_size = 0.005);

/// Draws the two colour maps side by side with iso-lines, the spectral locus and the space's RGB triangle to `png`
/// (gnuplot_process.h: nothing but `png` is left behind) and, if `csv` is not empty, writes the values there
/// (x, y, optimal, smooth). The plot destination and gnuplot are checked before the ~3 s computation. Throws
/// InputError if a file cannot be written, PlotError if gnuplot is missing or fails.
void write_gamut_figure(SpectralLibrary& library, const RgbUpsampler& upsampler, const std::filesystem::path& png,
                        const std::filesystem::path& csv);

}  // namespace rimu
