#include "spectral/upsample_report.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "spectral/error.h"
#include "spectral/gnuplot_process.h"

namespace rimu {

void write_upsample_report(std::ostream& out, const RgbUpsampler& upsampler, const Rgb& rgb,
                           const UpsampleReportOptions& options) {
  // A plot that cannot be drawn is refused before the report is printed.
  if (!options.plot_png.empty()) check_plot_destination(options.plot_png, {"", 0, "--plot"});
  // 1e30 bounds every component so that luminance and spectrum stay finite doubles (no "inf" is ever printed).
  for (double c : {rgb.r, rgb.g, rgb.b})
    if (!(std::abs(c) <= kMaxUpsampleComponent)) {
      std::ostringstream m;
      m << "expected three finite RGB components in [-1e30, 1e30]; got (" << rgb.r << ", " << rgb.g << ", " << rgb.b
        << ")";
      throw InputError({"", 0, "rgb"}, m.str());
    }
  std::vector<double> values(kUpsampleKnotCount);
  bool mapped = false;
  double delta_e = 0;
  Rgb back;
  if (options.emission) {
    const UpsampledEmission e = upsampler.upsample_emission(rgb);
    for (int i = 0; i < kUpsampleKnotCount; ++i) values[i] = e.spectrum.value(upsample_knot_nm(i));
    mapped = e.gamut_mapped, delta_e = e.delta_e2000;
    // Round trip of the chromaticity-carrying factor, scaled back to the input luminance.
    const Xyz shape = upsampler.xyz_of(e.spectrum.shape());
    const double y = upsampler.space().to_xyz(rgb).y;
    back = upsampler.space().from_xyz({shape.x * y, shape.y * y, shape.z * y});
  } else {
    const UpsampledReflectance r = upsampler.upsample_reflectance(rgb);
    for (int i = 0; i < kUpsampleKnotCount; ++i) values[i] = r.spectrum.samples().knot(i);
    mapped = r.gamut_mapped, delta_e = r.delta_e2000;
    back = upsampler.rgb_of(r.spectrum);
  }
  bool finite = std::isfinite(delta_e) && std::isfinite(back.r) && std::isfinite(back.g) && std::isfinite(back.b);
  for (double v : values) finite = finite && std::isfinite(v);
  if (!finite)
    throw InputError({"", 0, "rgb"}, "the upsampled spectrum or its round trip is not finite: the RGB is too extreme "
                                     "for this colour space");
  const char* unit = options.emission ? "W/(m2 sr nm) for RGB luminance in cd/m2" : "reflectance factor";
  if (options.csv) {
    out << "wavelength_nm," << (options.emission ? "spectral_radiance" : "reflectance") << '\n';
    for (int i = 0; i < kUpsampleKnotCount; ++i) out << upsample_knot_nm(i) << ',' << values[i] << '\n';
  } else {
    out << (options.emission ? "emission" : "reflectance") << " upsampled from " << upsampler.space().name() << " ("
        << rgb.r << ", " << rgb.g << ", " << rgb.b << "), table " << upsampler.table().white_name << "\n"
        << "  round trip RGB: (" << back.r << ", " << back.g << ", " << back.b << ")\n"
        << "  CIEDE2000 to input: " << delta_e << "\n"
        << "  gamut mapping acted: " << (mapped ? "yes" : "no") << "\n"
        << "  spectrum (" << unit << "):\n";
    for (int i = 0; i < kUpsampleKnotCount; ++i) out << "    " << upsample_knot_nm(i) << " nm  " << values[i] << '\n';
  }
  if (!options.plot_png.empty()) {
    std::ostringstream data, title;
    for (int i = 0; i < kUpsampleKnotCount; ++i) data << upsample_knot_nm(i) << ' ' << values[i] << '\n';
    title << upsampler.space().name() << " (" << rgb.r << ", " << rgb.g << ", " << rgb.b << ")"
          << (mapped ? ", gamut-mapped" : "");
    GnuplotJob job;
    job.terminal = "pngcairo size 900,500";
    job.data_files = {{"spectrum.dat", data.str()}};
    job.commands = "set xlabel 'wavelength (nm)'\nset ylabel " + gnuplot_text(unit) +
                   " noenhanced\nset xrange [360:830]\nset grid\nset key noenhanced\n"
                   "plot 'spectrum.dat' using 1:2 with lines lw 2 title " + gnuplot_text(title.str()) + "\n";
    run_gnuplot(job, options.plot_png);
  }
}

}  // namespace rimu
