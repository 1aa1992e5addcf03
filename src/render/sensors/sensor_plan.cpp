#include "render/sensors/sensor_plan.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "render/output/plot_output.h"

namespace rimu {
namespace {

std::string fixed(double x, int digits) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, x);
  return buffer;
}

// The points a plan draws, and how its title and legend name them.
struct PlanValues {
  const std::vector<MeterReading>* points;
  const char* symbol;  // E, E_s, E_mel
  const char* legend;  // the colour bar's label
};

PlanValues plan_values(const GridReadings& readings, PlanQuantity quantity) {
  switch (quantity) {
    case PlanQuantity::scotopic: return {&readings.scotopic_points, "Es", "scotopic illuminance (scotopic lx)"};
    case PlanQuantity::melanopic_edi: return {&readings.melanopic_points, "Emel", "melanopic EDI (lx)"};
    default: return {&readings.points, "E", "illuminance (lx)"};
  }
}

}  // namespace

GnuplotJob grid_plan_job(const IlluminanceGrid& grid, const GridReadings& readings, PlanQuantity quantity) {
  const PlanValues values = plan_values(readings, quantity);
  const std::vector<MeterReading>& points = *values.points;
  if (points.size() != size_t(grid.count_u) * size_t(grid.count_v))
    throw std::logic_error("grid_plan_job: the readings hold no points of the quantity asked for");
  double e_min = points.front().value, e_max = e_min, sum = 0.0;
  for (const MeterReading& p : points) {
    e_min = std::min(e_min, p.value);
    e_max = std::max(e_max, p.value);
    sum += p.value;
  }
  const double e_avg = sum / double(points.size()), u0 = e_avg > 0.0 ? e_min / e_avg : 0.0;
  const double cell_u = grid.size_u_m / grid.count_u, cell_v = grid.size_v_m / grid.count_v;
  // Rows of constant j separated by blank lines: the grid layout gnuplot's contouring needs.
  std::ostringstream data;
  for (int j = 0; j < grid.count_v; ++j) {
    for (int i = 0; i < grid.count_u; ++i)
      data << (i + 0.5) * cell_u << ' ' << (j + 0.5) * cell_v << ' '
           << points[size_t(j * grid.count_u + i)].value << '\n';
    data << '\n';
  }
  GnuplotJob job;
  const double aspect = double(grid.size_v_m) / double(grid.size_u_m);
  const int width = 900, height = std::clamp(int(700 * aspect) + 150, 300, 1400);
  job.terminal = "pngcairo size " + std::to_string(width) + "," + std::to_string(height);
  job.data_files = {{"grid.dat", data.str()}};
  std::ostringstream c;
  const bool contours = grid.count_u >= 2 && grid.count_v >= 2 && e_max > e_min;
  if (contours) {
    // Isolux lines: gnuplot's contouring of the grid, tabulated first and drawn over the cells.
    c << "set contour base\nset cntrparam levels auto 8\nunset surface\nset table 'contours.dat'\n"
         "splot 'grid.dat' using 1:2:3 with lines\nunset table\nunset contour\nset surface\n";
  }
  const std::string e = values.symbol;
  c << "set title " << gnuplot_text(grid.name + ": " + e + "min " + fixed(e_min, 1) + " lx, " + e + "avg " +
                                    fixed(e_avg, 1) + " lx, " + e + "max " + fixed(e_max, 1) + " lx, U0 " + fixed(u0, 2))
    << " noenhanced\n"
    << "set xlabel 'along u (m)'\nset ylabel 'along v (m)'\nset cblabel " << gnuplot_text(values.legend) << "\n"
    << "set size ratio -1\nset xrange [0:" << grid.size_u_m << "]\nset yrange [0:" << grid.size_v_m << "]\n"
    << false_colour_palette_command()
    << "set cbrange [" << e_min << ":" << std::max(e_max, e_min + 1e-9) << "]\n"
    << "set style fill solid 1.0 noborder\nunset key\n"
    << "plot 'grid.dat' using 1:2:(" << cell_u / 2 << "):(" << cell_v / 2 << "):3 with boxxyerror lc palette";
  if (contours)
    c << ", 'contours.dat' using 1:2 with lines lc 'black' lw 1, 'contours.dat' using 1:2:(sprintf('%.0f', $3)) every 30 "
         "with labels font ',8' tc 'black'";
  c << "\n";
  job.commands = c.str();
  return job;
}

void write_grid_plan(const std::filesystem::path& png, const IlluminanceGrid& grid, const GridReadings& readings,
                     PlanQuantity quantity) {
  draw_plot_png(grid_plan_job(grid, readings, quantity), png);
}

std::filesystem::path grid_plan_path(const std::filesystem::path& base, const IlluminanceGrid& grid,
                                     PlanQuantity quantity) {
  const char* suffix = quantity == PlanQuantity::scotopic        ? ".scotopic"
                       : quantity == PlanQuantity::melanopic_edi ? ".melanopic_edi"
                                                                 : "";
  return std::filesystem::path(base.string() + "." + grid.name + suffix + ".png");
}

}  // namespace rimu
