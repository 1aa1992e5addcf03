// rimu-colour: the colour-science toolkit's command line. It parses options and calls src/spectral.
//
// Exit codes (common/tool_main.h): 0 ok, 1 bad input (the message names the file/line/option), 2 runtime failure.
#include <iostream>

#include "common/tool_main.h"

#include "spectral/error.h"
#include "spectral/gamut_figure.h"
#include "spectral/rgb_upsampler.h"
#include "spectral/upsample_report.h"
#include "spectral/spectrum_report.h"
#include "spectral/spectrum_source.h"

namespace {

struct UpsampleFlags {
  bool emission = false;
  bool csv = false;
};

struct ReportOptions {
  std::string illuminant;
  double blackbody_k = 0, daylight_k = 0;
  std::string csv, column;
  bool json = false;
};

rimu::SpectrumSource source_from(const ReportOptions& o, int given) {
  if (given != 1)
    throw rimu::InputError({"", 0, "report"}, "give exactly one spectrum: an illuminant name, --blackbody K, "
                                              "--daylight K or --csv FILE");
  rimu::SpectrumSource s;
  if (!o.illuminant.empty()) {
    s.kind = rimu::SpectrumSource::Kind::named_illuminant;
    s.name = o.illuminant;
    s.where.key = "illuminant";
  } else if (!o.csv.empty()) {
    s.kind = rimu::SpectrumSource::Kind::csv_file;
    s.name = o.csv;
    s.column = o.column;
  } else if (o.blackbody_k != 0) {
    s.kind = rimu::SpectrumSource::Kind::blackbody;
    s.number = o.blackbody_k;
    s.where.key = "--blackbody";
  } else {
    s.kind = rimu::SpectrumSource::Kind::daylight;
    s.number = o.daylight_k;
    s.where.key = "--daylight";
  }
  return s;
}

struct Options {
  ReportOptions report;
  CLI::App *report_cmd = nullptr, *gamut_cmd = nullptr, *upsample_cmd = nullptr;
  CLI::Option *name_opt = nullptr, *bb_opt = nullptr, *dl_opt = nullptr, *csv_opt = nullptr;
  std::string gamut_png = "gamut.png", gamut_csv, gamut_space = "srgb-linear";
  std::vector<double> upsample_rgb;
  std::string upsample_space = "srgb-linear", upsample_plot;
  UpsampleFlags upsample_flags;
};

void declare(CLI::App& app, Options& o) {
  app.require_subcommand(0, 1);  // none is refused in run(), so that an unknown word is named as unknown
  ReportOptions& report = o.report;
  o.report_cmd = app.add_subcommand(
      "report", "XYZ, xy, u'v', CCT/Duv, luminous efficacy, CRI (Ra, R1-R14), sRGB and ACEScg of a light's spectrum");
  o.name_opt = o.report_cmd->add_option("illuminant", report.illuminant,
                                        "a CIE illuminant: A, D50, D65, E, F1-F12, FL3.1-FL3.15, HP1-HP5, LED-B1 ...");
  o.bb_opt = o.report_cmd->add_option("--blackbody", report.blackbody_k, "Planckian radiator at this temperature (K)");
  o.dl_opt = o.report_cmd->add_option("--daylight", report.daylight_k, "CIE daylight at this CCT (K), 4000-25000");
  o.csv_opt = o.report_cmd->add_option("--csv", report.csv, "a CSV file: wavelength_nm, then spectral power columns");
  o.report_cmd->add_option("--column", report.column, "which power column of --csv (default: the second column)");
  o.report_cmd->add_flag("--json", report.json, "print JSON instead of text");

  o.gamut_cmd = app.add_subcommand(
      "gamut", "plot the brightest reflectance per chromaticity: MacAdam's optimal colours vs the upsampler's smooth spectra");
  o.gamut_cmd->add_option("--out", o.gamut_png, "PNG to write (default gamut.png); gnuplot script and data go beside it");
  o.gamut_cmd->add_option("--csv", o.gamut_csv, "also write the values per chromaticity bin as CSV (default: beside the PNG)");
  o.gamut_cmd->add_option("--space", o.gamut_space, "colour space whose white and triangle are used (default srgb-linear)");

  o.upsample_cmd = app.add_subcommand(
      "upsample", "turn a linear RGB colour into a spectrum (Meng et al. 2015 smoothest spectra, gamut-mapped)");
  o.upsample_cmd->add_option("rgb", o.upsample_rgb, "three linear RGB components, e.g. 0.8 0.2 0.1")->expected(3)->required();
  o.upsample_cmd->add_option("--space", o.upsample_space,
                             "srgb-linear, rec2020, display-p3, aces2065-1, acescg or cie-rgb (default srgb-linear)");
  o.upsample_cmd->add_flag("--emission", o.upsample_flags.emission, "upsample as a light's colour (no reflectance limit)");
  o.upsample_cmd->add_flag("--csv", o.upsample_flags.csv, "print the spectrum as CSV only");
  o.upsample_cmd->add_option("--plot", o.upsample_plot, "also plot the spectrum to this PNG (gnuplot)");
}

void run(const Options& o) {
  if (!*o.report_cmd && !*o.gamut_cmd && !*o.upsample_cmd)
    throw rimu::InputError({}, "give a subcommand: report, gamut or upsample (see --help)");
  rimu::SpectralLibrary library = rimu::SpectralLibrary::at_default_location();
  if (*o.report_cmd) {
    const int given = int(o.name_opt->count() + o.bb_opt->count() + o.dl_opt->count() + o.csv_opt->count());
    const rimu::SpectrumSource source = source_from(o.report, given);
    const rimu::SpectrumReport r = rimu::analyse_spectrum(source, library);
    std::cout << (o.report.json ? rimu::report_json(r) : rimu::report_text(r));
  } else if (*o.gamut_cmd) {
    const rimu::RgbUpsampler upsampler(library, rimu::RgbColourSpace::named(o.gamut_space));
    const std::filesystem::path png = o.gamut_png;
    const std::filesystem::path csv = o.gamut_csv.empty() ? std::filesystem::path(png).replace_extension(".csv")
                                                          : std::filesystem::path(o.gamut_csv);
    rimu::write_gamut_figure(library, upsampler, png, csv);
    std::cout << "wrote " << png.string() << " and " << csv.string() << "\n";
  } else if (*o.upsample_cmd) {
    const rimu::RgbUpsampler upsampler(library, rimu::RgbColourSpace::named(o.upsample_space));
    rimu::UpsampleReportOptions options;
    options.emission = o.upsample_flags.emission;
    options.csv = o.upsample_flags.csv;
    if (!o.upsample_plot.empty()) options.plot_png = o.upsample_plot;
    rimu::write_upsample_report(std::cout, upsampler, {o.upsample_rgb[0], o.upsample_rgb[1], o.upsample_rgb[2]}, options);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  return rimu::run_tool({"rimu-colour", "rimu-colour: colorimetry of spectra (CIE 15, CIE 13.3) from Rimu's published tables"},
                        argc, argv, [&](CLI::App& app) { declare(app, options); }, [&] { run(options); });
}
