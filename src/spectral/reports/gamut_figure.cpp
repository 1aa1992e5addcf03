#include "spectral/reports/gamut_figure.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/error.h"
#include "spectral/io/gnuplot_process.h"
#include "spectral/io/output_file.h"

namespace rimu {
namespace {

constexpr double kMaxX = 0.75, kMaxY = 0.85;

}  // namespace

std::vector<GamutFigureBin> gamut_figure_bins(SpectralLibrary& library, const RgbUpsampler& upsampler, double bin_size) {
  const int nx = int(std::lround(kMaxX / bin_size)), ny = int(std::lround(kMaxY / bin_size));
  std::vector<GamutFigureBin> bins(size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) bins[size_t(j) * nx + i].xy = {(i + 0.5) * bin_size, (j + 0.5) * bin_size};

  // Per-nm XYZ weights W(λ)·cmf(λ)/Σ W ȳ, as prefix sums: a band's XYZ is a difference of two prefix sums.
  const Observer& observer = library.observer(StandardObserver::cie1931_2deg);
  const Spectrum& white = *upsampler.illuminant();
  const int count = 471;  // 360..830 nm
  std::vector<Xyz> prefix(count + 1);
  double norm = 0;
  for (int k = 0; k < count; ++k) norm += white.value(360.0 + k) * observer.y_bar.value(360.0 + k);
  for (int k = 0; k < count; ++k) {
    const double l = 360.0 + k, w = white.value(l) / norm;
    prefix[k + 1] = {prefix[k].x + w * observer.x_bar.value(l), prefix[k].y + w * observer.y_bar.value(l),
                     prefix[k].z + w * observer.z_bar.value(l)};
  }
  const Xyz total = prefix[count];
  auto record = [&](const Xyz& v) {
    const double sum = v.x + v.y + v.z;
    if (!(sum > 1e-9)) return;
    const int i = int(v.x / sum / bin_size), j = int(v.y / sum / bin_size);
    if (i < 0 || j < 0 || i >= nx || j >= ny) return;
    double& slot = bins[size_t(j) * nx + i].optimal_xyz_sum;
    slot = std::fmax(slot, sum);
  };
  // Band edges every 0.2 nm (prefix sums interpolated linearly): 1 nm edges leave empty bins in the green,
  // where the optimal colours' chromaticity moves fastest with the edges.
  const int edge_steps = 5;
  auto prefix_at = [&](int e) {
    const int k = e / edge_steps;
    const double t = double(e % edge_steps) / edge_steps;
    if (k >= count) return total;
    return Xyz{prefix[k].x + t * (prefix[k + 1].x - prefix[k].x), prefix[k].y + t * (prefix[k + 1].y - prefix[k].y),
               prefix[k].z + t * (prefix[k + 1].z - prefix[k].z)};
  };
  const int edges = count * edge_steps;
  std::vector<Xyz> at(edges + 1);
  for (int e = 0; e <= edges; ++e) at[e] = prefix_at(e);
  for (int a = 0; a < edges; ++a)
    for (int b = a + 1; b <= edges; ++b) {
      const Xyz band{at[b].x - at[a].x, at[b].y - at[a].y, at[b].z - at[a].z};
      record(band);
      record({total.x - band.x, total.y - band.y, total.z - band.z});
    }

  // The smooth limit: the Y = 1 smooth spectrum scaled to peak 1 has Y = 1/peak, so X+Y+Z = 1/(peak·y).
  const KnotGamut& gamut = upsampler.gamut();
  for (GamutFigureBin& bin : bins) {
    if (gamut.relative_radius(bin.xy) > upsampler.table().usable_fraction) continue;
    const KnotValues s = upsampler.smooth_shape(bin.xy);
    double peak = 0;
    for (double v : s) peak = std::fmax(peak, v);
    bin.smooth_xyz_sum = 1.0 / (peak * bin.xy.y);
  }
  return bins;
}

void write_gamut_figure(SpectralLibrary& library, const RgbUpsampler& upsampler, const std::filesystem::path& png,
                        const std::filesystem::path& csv) {
  check_plot_destination(png, {"", 0, "--out"});
  if (const auto folder = csv.parent_path(); !csv.empty() && !folder.empty() && !std::filesystem::is_directory(folder))
    throw InputError({csv.string(), 0, "--csv"}, "the folder '" + folder.string() + "' does not exist");
  if (!csv.empty()) {
    check_output_path(csv);
    if (same_output_file(csv, png))
      throw InputError({csv.string(), 0, "--csv"}, "--out and --csv name the same file; the plot would replace the table");
  }
  const double bin_size = 0.005;
  const auto bins = gamut_figure_bins(library, upsampler, bin_size);
  if (!csv.empty()) {
    std::ostringstream out;
    out << "# brightest reflectance per xy bin, X+Y+Z with white Y = 1, under the white of " << upsampler.space().name()
        << "; -1 = none\nx,y,optimal_xyz_sum,smooth_xyz_sum\n";
    for (const auto& b : bins) out << b.xy.x << ',' << b.xy.y << ',' << b.optimal_xyz_sum << ',' << b.smooth_xyz_sum << '\n';
    write_text_file(csv, out.str());  // whole or not at all; a full disk is an OutputError naming the file
  }
  // gnuplot inputs: a grid file (blank line between rows, NaN for empty bins), the locus, the triangle.
  std::ostringstream grid, locus, triangle;
  const int nx = int(std::lround(kMaxX / bin_size));
  for (size_t k = 0; k < bins.size(); ++k) {
    if (k > 0 && k % nx == 0) grid << '\n';
    auto value = [](double v) { return v < 0 ? std::string("NaN") : std::to_string(v); };
    grid << bins[k].xy.x << ' ' << bins[k].xy.y << ' ' << value(bins[k].optimal_xyz_sum) << ' '
         << value(bins[k].smooth_xyz_sum) << '\n';
  }
  const Observer& o = library.observer(StandardObserver::cie1931_2deg);
  for (int nm = 380; nm <= 700; ++nm) {
    const Chromaticity c = chromaticity_of(Xyz{o.x_bar.value(nm), o.y_bar.value(nm), o.z_bar.value(nm)});
    locus << c.x << ' ' << c.y << '\n';
  }
  const Chromaticity first = chromaticity_of(Xyz{o.x_bar.value(380), o.y_bar.value(380), o.z_bar.value(380)});
  locus << first.x << ' ' << first.y << '\n';
  const RgbColourSpace& s = upsampler.space();
  for (Chromaticity c : {s.red(), s.green(), s.blue(), s.red()}) triangle << c.x << ' ' << c.y << '\n';

  GnuplotJob job;
  job.terminal = "pngcairo size 1600,760 font ',11'";
  job.data_files = {{"grid.dat", grid.str()}, {"locus.dat", locus.str()}, {"triangle.dat", triangle.str()}};
  std::ostringstream g;
  g << "set multiplot layout 1,2\nset view map\nset size ratio -1\nset xrange [0:0.75]\nset yrange [0:0.85]\n"
    << "set xlabel 'x'\nset ylabel 'y'\nset cbrange [0:3.1]\nset cblabel 'max X+Y+Z (white Y = 1)'\n"
    << "set palette rgbformulae 33,13,10\nset contour base\nset cntrparam levels incremental 0.25,0.25,3\n"
    << "unset clabel\nset style increment default\nset key noenhanced\n";
  for (int panel = 0; panel < 2; ++panel) {
    const std::string title = std::string(panel == 0 ? "optimal (MacAdam) reflectances" : "smooth upsampled reflectances") +
                              " under " + upsampler.table().white_name;
    const char* column = panel == 0 ? "3" : "4";
    g << "set title " << gnuplot_text(title) << " noenhanced\n"
      << "splot 'grid.dat' using 1:2:" << column << " with pm3d notitle, 'grid.dat' using 1:2:" << column
      << " with lines lc rgb 'black' nosurface notitle, 'locus.dat' using 1:2:(0) with lines lw 2 lc rgb 'black'"
      << " nocontour notitle, 'triangle.dat' using 1:2:(0) with lines lw 2 lc rgb 'white' nocontour title "
      << gnuplot_text(s.name()) << "\n";
  }
  g << "unset multiplot";
  job.commands = g.str();
  run_gnuplot(job, png);
}

}  // namespace rimu
