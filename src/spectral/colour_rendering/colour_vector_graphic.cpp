#include "spectral/colour_rendering/colour_vector_graphic.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "spectral/io/gnuplot_process.h"

namespace rimu {

std::array<CvgBin, kTm30HueBins> colour_vector_graphic_bins(const ColourFidelity& fidelity) {
  std::array<CvgBin, kTm30HueBins> out{};
  for (int j = 0; j < kTm30HueBins; ++j) {
    const HueBin& b = fidelity.bins[size_t(j)];
    const double chroma = std::hypot(b.reference_a, b.reference_b);
    if (!(chroma > 0)) continue;  // an empty bin; never with the 99 CES (every bin holds at least 3)
    // Dividing both averages by the reference chroma puts the reference on the unit circle at its own hue and
    // keeps the test vertex's offset equal to the shift the hue-bin table reports.
    out[size_t(j)] = {b.reference_a / chroma, b.reference_b / chroma, b.test_a / chroma, b.test_b / chroma};
  }
  return out;
}

void write_colour_vector_graphic(const ColourFidelity& fidelity, const std::string& description,
                                 const std::filesystem::path& png) {
  check_plot_destination(png, {"", 0, "--graphic"});
  const auto bins = colour_vector_graphic_bins(fidelity);
  std::ostringstream polygon, arrows, labels, spokes;
  polygon.precision(9);
  arrows.precision(9);
  for (int j = 0; j <= kTm30HueBins; ++j) {  // closed: the first vertex again at the end
    const CvgBin& b = bins[size_t(j % kTm30HueBins)];
    polygon << b.test_x << ' ' << b.test_y << '\n';
  }
  for (const CvgBin& b : bins)
    arrows << b.reference_x << ' ' << b.reference_y << ' ' << b.test_x - b.reference_x << ' '
           << b.test_y - b.reference_y << '\n';
  // Bin numbers at the middle of each 22.5° sector, outside the circle; sector edges as faint spokes.
  const double width = 2.0 * std::numbers::pi / kTm30HueBins;
  for (int j = 0; j < kTm30HueBins; ++j) {
    const double mid = (j + 0.5) * width, edge = j * width;
    labels << 1.38 * std::cos(mid) << ' ' << 1.38 * std::sin(mid) << ' ' << j + 1 << '\n';
    spokes << "0 0\n" << 1.5 * std::cos(edge) << ' ' << 1.5 * std::sin(edge) << "\n\n";
  }
  char indices[96];
  std::snprintf(indices, sizeof indices, "Rf %.0f   Rg %.0f   CCT %.0f K   Duv %.4f", fidelity.rf, fidelity.rg,
                fidelity.cct.cct_k, fidelity.cct.duv);

  GnuplotJob job;
  job.terminal = "pngcairo size 760,800 font ',11'";
  job.data_files = {{"test.dat", polygon.str()}, {"arrows.dat", arrows.str()}, {"labels.dat", labels.str()},
                    {"spokes.dat", spokes.str()}};
  std::ostringstream g;
  g << "set size ratio -1\nset xrange [-1.5:1.5]\nset yrange [-1.5:1.5]\n"
    << "set xlabel \"a' / reference chroma (CAM02-UCS)\" noenhanced\n"
    << "set ylabel \"b' / reference chroma (CAM02-UCS)\" noenhanced\n"
    << "set title " << gnuplot_text("TM-30 colour vector graphic: " + description) << ".\"\\n\"."
    << gnuplot_text(indices) << " noenhanced\n"
    << "set key bottom right noenhanced\nset parametric\nset trange [0:2*pi]\nset samples 361\n"
    << "plot 'spokes.dat' using 1:2 with lines lc rgb '#cccccc' notitle, "
    << "cos(t), sin(t) with lines lw 2 lc rgb 'black' title 'reference', "
    << "'test.dat' using 1:2 with lines lw 2 lc rgb '#d62728' title 'test', "
    << "'arrows.dat' using 1:2:3:4 with vectors head filled size 0.05,20 lw 1.5 lc rgb '#d62728' notitle, "
    << "'labels.dat' using 1:2:3 with labels notitle\n";
  job.commands = g.str();
  run_gnuplot(job, png);
}

}  // namespace rimu
