#include "render/sensors/sensor_plan.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "render/output/plot_output.h"

namespace rimu {
namespace {

std::string fixed(double x, int digits) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, x);
  return buffer;
}

}  // namespace

GnuplotJob grid_plan_job(const IlluminanceGrid& grid, const GridReadings& readings) {
  const double cell_u = grid.size_u_m / grid.count_u, cell_v = grid.size_v_m / grid.count_v;
  // Rows of constant j separated by blank lines: the grid layout gnuplot's contouring needs.
  std::ostringstream data;
  for (int j = 0; j < grid.count_v; ++j) {
    for (int i = 0; i < grid.count_u; ++i)
      data << (i + 0.5) * cell_u << ' ' << (j + 0.5) * cell_v << ' '
           << readings.points[size_t(j * grid.count_u + i)].value << '\n';
    data << '\n';
  }
  GnuplotJob job;
  const double aspect = double(grid.size_v_m) / double(grid.size_u_m);
  const int width = 900, height = std::clamp(int(700 * aspect) + 150, 300, 1400);
  job.terminal = "pngcairo size " + std::to_string(width) + "," + std::to_string(height);
  job.data_files = {{"grid.dat", data.str()}};
  std::ostringstream c;
  const bool contours = grid.count_u >= 2 && grid.count_v >= 2 && readings.e_max_lx > readings.e_min_lx;
  if (contours) {
    // Isolux lines: gnuplot's contouring of the grid, tabulated first and drawn over the cells.
    c << "set contour base\nset cntrparam levels auto 8\nunset surface\nset table 'contours.dat'\n"
         "splot 'grid.dat' using 1:2:3 with lines\nunset table\nunset contour\nset surface\n";
  }
  c << "set title " << gnuplot_text(grid.name + ": Emin " + fixed(readings.e_min_lx, 1) + " lx, Eavg " +
                                    fixed(readings.e_avg_lx, 1) + " lx, Emax " + fixed(readings.e_max_lx, 1) +
                                    " lx, U0 " + fixed(readings.u0, 2))
    << " noenhanced\n"
    << "set xlabel 'along u (m)'\nset ylabel 'along v (m)'\nset cblabel 'illuminance (lx)'\n"
    << "set size ratio -1\nset xrange [0:" << grid.size_u_m << "]\nset yrange [0:" << grid.size_v_m << "]\n"
    << false_colour_palette_command()
    << "set cbrange [" << readings.e_min_lx << ":" << std::max(readings.e_max_lx, readings.e_min_lx + 1e-9) << "]\n"
    << "set style fill solid 1.0 noborder\nunset key\n"
    << "plot 'grid.dat' using 1:2:(" << cell_u / 2 << "):(" << cell_v / 2 << "):3 with boxxyerror lc palette";
  if (contours)
    c << ", 'contours.dat' using 1:2 with lines lc 'black' lw 1, 'contours.dat' using 1:2:(sprintf('%.0f', $3)) every 30 "
         "with labels font ',8' tc 'black'";
  c << "\n";
  job.commands = c.str();
  return job;
}

void write_grid_plan(const std::filesystem::path& png, const IlluminanceGrid& grid, const GridReadings& readings) {
  draw_plot_png(grid_plan_job(grid, readings), png);
}

std::filesystem::path grid_plan_path(const std::filesystem::path& base, const IlluminanceGrid& grid) {
  return std::filesystem::path(base.string() + "." + grid.name + ".png");
}

}  // namespace rimu
