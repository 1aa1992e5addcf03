#include "spectral/reports/upsample_report.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/error.h"
#include "spectral/io/gnuplot_process.h"

namespace rimu {

UpsampledColour upsample_colour(const RgbUpsampler& upsampler, const Rgb& rgb, bool emission,
                                const SourceLocation& where) {
  // kMaxColourComponent bounds every component so that luminance and spectrum stay finite doubles.
  check_colour_components(rgb.r, rgb.g, rgb.b, where);
  UpsampledColour c;
  c.knot_values.resize(kUpsampleKnotCount);
  if (emission) {
    const UpsampledEmission e = upsampler.upsample_emission(rgb, where);
    for (int i = 0; i < kUpsampleKnotCount; ++i) c.knot_values[i] = e.spectrum.value(upsample_knot_nm(i));
    c.gamut_mapped = e.gamut_mapped, c.delta_e2000 = e.delta_e2000;
    // Round trip of the chromaticity-carrying factor, scaled back to the input luminance.
    const Xyz shape = upsampler.xyz_of(e.spectrum.shape());
    const double y = upsampler.space().to_xyz(rgb).y;
    c.round_trip = upsampler.space().from_xyz({shape.x * y, shape.y * y, shape.z * y});
    c.spectrum = std::make_shared<EmissionSpectrum>(e.spectrum);
  } else {
    const UpsampledReflectance r = upsampler.upsample_reflectance(rgb, where);
    for (int i = 0; i < kUpsampleKnotCount; ++i) c.knot_values[i] = r.spectrum.samples().knot(i);
    c.gamut_mapped = r.gamut_mapped, c.delta_e2000 = r.delta_e2000;
    c.round_trip = upsampler.rgb_of(r.spectrum);
    c.spectrum = std::make_shared<ReflectanceSpectrum>(r.spectrum);
  }
  bool finite = std::isfinite(c.delta_e2000) && std::isfinite(c.round_trip.r) && std::isfinite(c.round_trip.g) &&
                std::isfinite(c.round_trip.b);
  for (double v : c.knot_values) finite = finite && std::isfinite(v);
  if (!finite)
    throw InputError(where, "the upsampled spectrum or its round trip is not finite: the RGB is too extreme for "
                            "this colour space");
  return c;
}

void write_upsample_report(std::ostream& out, const RgbUpsampler& upsampler, const Rgb& rgb,
                           const UpsampleReportOptions& options) {
  // A plot that cannot be drawn is refused before the report is printed.
  if (!options.plot_png.empty()) check_plot_destination(options.plot_png, {"", 0, "--plot"});
  const UpsampledColour c = upsample_colour(upsampler, rgb, options.emission, {"", 0, "rgb"});
  const std::vector<double>& values = c.knot_values;
  const bool mapped = c.gamut_mapped;
  const double delta_e = c.delta_e2000;
  const Rgb& back = c.round_trip;
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
