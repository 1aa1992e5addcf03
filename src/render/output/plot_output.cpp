#include "render/output/plot_output.h"

#include <algorithm>
#include <cstdio>

#include "spectral/error.h"

namespace rimu {

void check_plot_png(const std::filesystem::path& png, const SourceLocation& where) {
  try {
    check_plot_destination(png, where);
  } catch (const PlotError& e) {
    throw RenderError(e.what());
  }
}

const std::array<PaletteStop, 5>& false_colour_palette() {
  static const std::array<PaletteStop, 5> stops{{{0.00, {0x44, 0x01, 0x54}},
                                                 {0.25, {0x3b, 0x52, 0x8b}},
                                                 {0.50, {0x21, 0x91, 0x8c}},
                                                 {0.75, {0x5e, 0xc9, 0x62}},
                                                 {1.00, {0xfd, 0xe7, 0x25}}}};
  return stops;
}

std::string false_colour_palette_command() {
  std::string command = "set palette defined (";
  for (const PaletteStop& stop : false_colour_palette()) {
    char entry[48];
    std::snprintf(entry, sizeof entry, "%s%g '#%02x%02x%02x'", stop.position > 0 ? ", " : "", stop.position,
                  stop.rgb[0], stop.rgb[1], stop.rgb[2]);
    command += entry;
  }
  return command + ")\n";
}

std::array<double, 3> false_colour_rgb(double position) {
  const auto& stops = false_colour_palette();
  const double t = std::clamp(position, 0.0, 1.0);
  size_t k = 1;
  while (k + 1 < stops.size() && t > stops[k].position) ++k;
  const PaletteStop &a = stops[k - 1], &b = stops[k];
  const double f = (t - a.position) / (b.position - a.position);
  std::array<double, 3> rgb{};
  for (int c = 0; c < 3; ++c) rgb[size_t(c)] = a.rgb[size_t(c)] + f * (b.rgb[size_t(c)] - a.rgb[size_t(c)]);
  return rgb;
}

void draw_plot_png(const GnuplotJob& job, const std::filesystem::path& png) {
  try {
    run_gnuplot(job, png);
  } catch (const PlotError& e) {
    throw RenderError(e.what());
  }
}

}  // namespace rimu
