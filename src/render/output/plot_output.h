// Plots drawn by rimu_render's tools (spectra, IES polar plots) through spectral/io/gnuplot_process.h, with its
// PlotError reported in this library's style (RenderError: tools exit with status 2).
#pragma once

#include <filesystem>

#include "spectral/error.h"
#include "spectral/io/gnuplot_process.h"

namespace rimu {

/// check_plot_destination(): InputError at `where` for a path that cannot be written, RenderError when gnuplot is
/// missing. Tools call it before they write or compute anything else.
void check_plot_png(const std::filesystem::path& png, const SourceLocation& where);

/// run_gnuplot(), a gnuplot failure as RenderError (the message names the PNG and carries gnuplot's output).
void draw_plot_png(const GnuplotJob& job, const std::filesystem::path& png);

}  // namespace rimu
