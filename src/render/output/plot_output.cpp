#include "render/output/plot_output.h"

#include "spectral/error.h"

namespace rimu {

void check_plot_png(const std::filesystem::path& png, const SourceLocation& where) {
  try {
    check_plot_destination(png, where);
  } catch (const PlotError& e) {
    throw RenderError(e.what());
  }
}

void draw_plot_png(const GnuplotJob& job, const std::filesystem::path& png) {
  try {
    run_gnuplot(job, png);
  } catch (const PlotError& e) {
    throw RenderError(e.what());
  }
}

}  // namespace rimu
