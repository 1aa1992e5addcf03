// The ANSI/IES TM-30-20 colour vector graphic (CVG): the 16 hue bins of a light's colour fidelity result drawn
// in CAM02-UCS a'b', each bin normalised by the chroma of its reference average so the reference is the unit circle.
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "spectral/colour_rendering/colour_fidelity.h"

namespace rimu {

/// One bin of the graphic in normalised a'b' (dimensionless: divided by the bin's reference chroma C_r,hj).
struct CvgBin {
  double reference_x = 0, reference_y = 0;  ///< (cos h_r, sin h_r): the reference average's hue on the unit circle
  double test_x = 0, test_y = 0;            ///< the test average / C_r,hj = reference point + (Δa', Δb') / C_r,hj
};

/// The normalised coordinates the graphic plots, in bin order (bin 1 starts at hue 0°, bins go counter-clockwise).
/// TM-30-20 §4.4: the test vertex is the reference vertex on the unit circle plus the bin's average shift divided
/// by the reference chroma, so its offset along / across the bin's bisecting hue is R_cs,hj / R_hs,hj.
std::array<CvgBin, kTm30HueBins> colour_vector_graphic_bins(const ColourFidelity& fidelity);

/// Draws the graphic to `png` with gnuplot (gnuplot_process.h): the unit circle (reference), the test polygon, an
/// arrow per bin from reference to test, the bin numbers, and R_f, R_g and `description` in the title; equal axis
/// scales. Throws InputError if `png` is not a writable file path (callers check it with check_plot_destination()
/// before computing, as this does again), PlotError if gnuplot is missing or fails.
void write_colour_vector_graphic(const ColourFidelity& fidelity, const std::string& description,
                                 const std::filesystem::path& png);

}  // namespace rimu
