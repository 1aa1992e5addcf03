// rimu-colour: the colour-science toolkit's command line. It parses options and calls src/spectral.
//
// Exit codes (common/tool_main.h): 0 ok, 1 bad input (the message names the file/line/option), 2 runtime failure.
#include <iostream>
#include <optional>

#include "common/tool_main.h"

#include "spectral/library/colorimetry_options.h"
#include "spectral/colour_rendering/colour_fidelity.h"
#include "spectral/colour_rendering/colour_vector_graphic.h"
#include "spectral/error.h"
#include "spectral/reports/gamut_figure.h"
#include "spectral/io/gnuplot_process.h"
#include "spectral/io/output_file.h"
#include "spectral/reports/reflectance_report.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "spectral/reports/upsample_report.h"
#include "spectral/reports/spectrum_report.h"
#include "spectral/library/spectrum_source.h"
#include "spectral/colorimetry/tristimulus_method.h"

namespace {

struct UpsampleFlags {
  bool emission = false;
  bool csv = false;
};

struct ReportOptions {
  std::string illuminant;
  double blackbody_k = 0, daylight_k = 0;
  bool blackbody_given = false;  ///< --blackbody was given (its value may read as 0: 1e-400 underflows)
  std::string csv, column;
  std::string method, bandpass_corrected;
  bool json = false;
};

struct ReflectanceOptions {
  std::string csv, column, patch, illuminant = "D50", method, reference, reference_column, bandpass_corrected;
  int observer = 2;
  bool json = false;
};

/// --method NAME as a TristimulusMethod; empty when not given (or "auto").
std::optional<rimu::TristimulusMethod> method_option(const std::string& text) {
  return rimu::tristimulus_method_option(text, {"", 0, "--method"});
}

/// --bandpass-corrected yes|no: which ASTM E308 table (Table 6 for corrected data, Table 5 for uncorrected data).
rimu::E308Table e308_table_option(const std::string& text) {
  if (text.empty() || text == "yes") return rimu::E308Table::table6_bandpass_corrected;
  if (text == "no") return rimu::E308Table::table5_uncorrected;
  throw rimu::InputError({"", 0, "--bandpass-corrected"}, "expected yes or no, got '" + text + "'");
}

/// --bandpass-corrected only means something for the E308 weights: refuse it when another method was used.
void check_bandpass_option(const std::string& text, bool used_e308, const std::string& method) {
  if (!text.empty() && !used_e308)
    throw rimu::InputError({"", 0, "--bandpass-corrected"},
                           "chooses between ASTM E308 Table 6 (yes) and Table 5 (no), but these data are summed by "
                           "the '" + method + "' method; it applies to --method astm-e308 (10 and 20 nm data)");
}

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
  } else if (o.blackbody_given) {
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
  ReportOptions report, fidelity;
  ReflectanceOptions refl;
  CLI::App *report_cmd = nullptr, *fidelity_cmd = nullptr, *refl_cmd = nullptr, *gamut_cmd = nullptr,
           *upsample_cmd = nullptr;
  CLI::Option *name_opt = nullptr, *bb_opt = nullptr, *dl_opt = nullptr, *csv_opt = nullptr;
  CLI::Option *fid_name = nullptr, *fid_csv = nullptr, *refl_csv = nullptr, *refl_patch = nullptr;
  std::string gamut_png = "gamut.png", gamut_csv, gamut_space = "srgb-linear";
  std::vector<double> upsample_rgb;
  std::string upsample_space = "srgb-linear", upsample_plot;
  std::string fidelity_graphic;
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
  o.report_cmd->add_option("--bandpass-corrected", report.bandpass_corrected,
                           "yes (default): the data were corrected for the instrument's bandpass, or measured with a "
                           "narrow one: ASTM E308 Table 6. no: uncorrected data from an instrument whose triangular "
                           "bandpass equals the interval: Table 5. Only with --method astm-e308 (10/20 nm data)");
  o.report_cmd->add_option("--method", report.method,
                           "tristimulus summation: native (the data's own 1/5 nm wavelengths), 1nm (interpolate to "
                           "1 nm) or astm-e308 (10/20 nm data); default from the data's spacing");

  ReflectanceOptions& refl = o.refl;
  o.refl_cmd = app.add_subcommand(
      "reflectance", "XYZ, xyY, CIELAB, encoded sRGB (and ΔE76/ΔE2000 against --reference) of a reflectance or "
                     "transmittance factor under a CIE illuminant");
  o.refl_csv = o.refl_cmd->add_option("--csv", refl.csv, "a CSV file: wavelength_nm, then reflectance factors (0-1)");
  o.refl_cmd->add_option("--column", refl.column, "which column of --csv (default: the second column)");
  o.refl_patch = o.refl_cmd->add_option("--patch", refl.patch,
                                        "a ColorChecker Classic patch (BabelColor average), e.g. \"dark skin\"");
  o.refl_cmd->add_option("--illuminant", refl.illuminant, "CIE illuminant the sample is seen under (default D50)");
  o.refl_cmd->add_option("--observer", refl.observer, "2 (CIE 1931, default) or 10 (CIE 1964)");
  o.refl_cmd->add_option("--method", refl.method, "auto (default: from the data's spacing), native, 1nm or astm-e308");
  o.refl_cmd->add_option("--bandpass-corrected", refl.bandpass_corrected,
                         "yes (default): the data were corrected for the instrument's bandpass, or measured with a "
                           "narrow one: ASTM E308 Table 6. no: uncorrected data from an instrument whose triangular "
                           "bandpass equals the interval: Table 5. Only with --method astm-e308 (10/20 nm data)");
  o.refl_cmd->add_option("--reference", refl.reference, "a second reflectance CSV to compare against (ΔE)");
  o.refl_cmd->add_option("--reference-column", refl.reference_column, "which column of --reference");
  o.refl_cmd->add_flag("--json", refl.json, "print JSON instead of text");

  ReportOptions& fidelity = o.fidelity;
  o.fidelity_cmd = app.add_subcommand(
      "fidelity", "colour fidelity Rf (CIE 224:2017 / TM-30-20), gamut index Rg and the 16 hue bins of a light");
  o.fid_name = o.fidelity_cmd->add_option("illuminant", fidelity.illuminant, "a CIE illuminant, e.g. F2 or LED-B3");
  o.fid_csv = o.fidelity_cmd->add_option("--csv", fidelity.csv, "a CSV file: wavelength_nm, then spectral power");
  o.fidelity_cmd->add_option("--column", fidelity.column, "which power column of --csv (default: the second column)");
  o.fidelity_cmd->add_flag("--json", fidelity.json, "print JSON instead of text");
  o.fidelity_cmd->add_option("--graphic", o.fidelity_graphic, "also draw the TM-30 colour vector graphic to this PNG");

  o.gamut_cmd = app.add_subcommand(
      "gamut", "plot the brightest reflectance per chromaticity: MacAdam's optimal colours vs the upsampler's smooth spectra");
  o.gamut_cmd->add_option("--out", o.gamut_png, "PNG to write (default gamut.png)");
  o.gamut_cmd->add_option("--csv", o.gamut_csv, "also write the values per chromaticity bin to this CSV file");
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
  if (!*o.report_cmd && !*o.fidelity_cmd && !*o.refl_cmd && !*o.gamut_cmd && !*o.upsample_cmd)
    throw rimu::InputError({}, "give a subcommand: report, reflectance, fidelity, gamut or upsample (see --help)");
  rimu::SpectralLibrary library = rimu::SpectralLibrary::at_default_location();
  if (*o.report_cmd) {
    const int given = int(o.name_opt->count() + o.bb_opt->count() + o.dl_opt->count() + o.csv_opt->count());
    ReportOptions report = o.report;
    report.blackbody_given = o.bb_opt->count() > 0;
    const rimu::SpectrumSource source = source_from(report, given);
    const rimu::SpectrumReport r = rimu::analyse_spectrum(source, library, method_option(o.report.method),
                                                          e308_table_option(o.report.bandpass_corrected));
    check_bandpass_option(o.report.bandpass_corrected, r.e308_table.has_value(), r.tristimulus_method);
    std::cout << (o.report.json ? rimu::report_json(r) : rimu::report_text(r));
  } else if (*o.fidelity_cmd) {
    // A graphic that cannot be drawn is refused before anything is computed or printed.
    if (!o.fidelity_graphic.empty()) {
      rimu::check_plot_destination(o.fidelity_graphic, {"", 0, "--graphic"});
      rimu::check_output_not_input(o.fidelity_graphic, "--graphic", {{o.fidelity.csv, "--csv"}});
    }
    const rimu::SpectrumSource source = source_from(o.fidelity, int(o.fid_name->count() + o.fid_csv->count()));
    const rimu::SpectrumPtr spectrum = rimu::make_emission_spectrum(source, library);
    const rimu::ColourFidelity f = rimu::ColourFidelityEvaluator(library).evaluate(*spectrum);
    std::cout << (o.fidelity.json ? rimu::colour_fidelity_json(f, source.describe())
                                  : rimu::colour_fidelity_text(f, source.describe()));
    if (!o.fidelity_graphic.empty()) rimu::write_colour_vector_graphic(f, source.describe(), o.fidelity_graphic);
  } else if (*o.refl_cmd) {
    const ReflectanceOptions& refl = o.refl;
    if (o.refl_csv->count() + o.refl_patch->count() != 1)
      throw rimu::InputError({"", 0, "reflectance"}, "give exactly one sample: --csv FILE or --patch NAME");
    rimu::ReflectanceConditions conditions;
    conditions.illuminant = refl.illuminant;
    conditions.observer = rimu::standard_observer_option(refl.observer, {"", 0, "--observer"});
    conditions.method = method_option(refl.method);
    conditions.e308_table = e308_table_option(refl.bandpass_corrected);
    const rimu::TabulatedSpectrum sample = refl.csv.empty() ? rimu::colorchecker_patch(library, refl.patch, {"", 0, "--patch"})
                                                            : rimu::load_reflectance_csv(refl.csv, refl.column);
    std::optional<rimu::TabulatedSpectrum> reference;
    if (!refl.reference.empty()) reference = rimu::load_reflectance_csv(refl.reference, refl.reference_column);
    const rimu::ReflectanceReport r =
        rimu::analyse_reflectance(sample, reference ? &*reference : nullptr, conditions, library);
    check_bandpass_option(refl.bandpass_corrected, r.sample.e308_table.has_value(), r.sample.method);
    std::cout << (refl.json ? rimu::reflectance_report_json(r) : rimu::reflectance_report_text(r));
  } else if (*o.gamut_cmd) {
    const rimu::RgbUpsampler upsampler(library, rimu::RgbColourSpace::named(o.gamut_space));
    rimu::write_gamut_figure(library, upsampler, o.gamut_png, o.gamut_csv);
    std::cout << "wrote " << o.gamut_png << (o.gamut_csv.empty() ? "" : " and " + o.gamut_csv) << "\n";
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
