// Plots drawn by rimu_render's tools (spectra, IES polar plots, false colour) through spectral/io/gnuplot_process.h,
// with its PlotError reported in this library's style (RenderError: tools exit with status 2).
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "spectral/error.h"
#include "spectral/io/gnuplot_process.h"

namespace rimu {

/// check_plot_destination(): InputError at `where` for a path that cannot be written, RenderError when gnuplot is
/// missing. Tools call it before they write or compute anything else.
void check_plot_png(const std::filesystem::path& png, const SourceLocation& where);

/// The false-colour scale every Rimu plan and false-colour image uses, so one colour means one position on every
/// legend: matplotlib's viridis (perceptually ordered, readable in grey and by colour-blind readers), given by its
/// end points and quartiles and interpolated linearly in 8-bit RGB between them, as gnuplot's `set palette defined`
/// does.
struct PaletteStop {
  double position;         ///< in [0, 1]
  std::array<int, 3> rgb;  ///< 0-255
};
const std::array<PaletteStop, 5>& false_colour_palette();
/// The gnuplot command that sets this palette: "set palette defined (0 '#440154', ...)".
std::string false_colour_palette_command();
/// The palette's colour at `position` (clamped to [0, 1]), 0-255 per channel before rounding.
std::array<double, 3> false_colour_rgb(double position);

/// run_gnuplot(), a gnuplot failure as RenderError (the message names the PNG and carries gnuplot's output).
void draw_plot_png(const GnuplotJob& job, const std::filesystem::path& png);

}  // namespace rimu
