// rimu-colour: the colour-science toolkit's command line. It parses options and calls src/spectral.
//
// Exit codes: 0 ok, 1 bad input (the message names the file/line/option), 2 runtime failure.
#include <CLI/CLI.hpp>

#include <iostream>

#include "spectral/error.h"
#include "spectral/spectrum_report.h"
#include "spectral/spectrum_source.h"

namespace {

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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rimu-colour: colorimetry of spectra (CIE 15, CIE 13.3) from Rimu's published tables"};
  app.require_subcommand(1);

  ReportOptions report;
  CLI::App* report_cmd = app.add_subcommand(
      "report", "XYZ, xy, u'v', CCT/Duv, luminous efficacy, CRI (Ra, R1-R14), sRGB and ACEScg of a light's spectrum");
  auto* name_opt = report_cmd->add_option("illuminant", report.illuminant,
                                          "a CIE illuminant: A, D50, D65, E, F1-F12, FL3.1-FL3.15, HP1-HP5, LED-B1 ...");
  auto* bb_opt = report_cmd->add_option("--blackbody", report.blackbody_k, "Planckian radiator at this temperature (K)");
  auto* dl_opt = report_cmd->add_option("--daylight", report.daylight_k, "CIE daylight at this CCT (K), 4000-25000");
  auto* csv_opt = report_cmd->add_option("--csv", report.csv, "a CSV file: wavelength_nm, then spectral power columns");
  report_cmd->add_option("--column", report.column, "which power column of --csv (default: the second column)");
  report_cmd->add_flag("--json", report.json, "print JSON instead of text");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }

  try {
    rimu::SpectralLibrary library = rimu::SpectralLibrary::at_default_location();
    if (*report_cmd) {
      const int given = int(name_opt->count() + bb_opt->count() + dl_opt->count() + csv_opt->count());
      const rimu::SpectrumSource source = source_from(report, given);
      const rimu::SpectrumReport r = rimu::analyse_spectrum(source, library);
      std::cout << (report.json ? rimu::report_json(r) : rimu::report_text(r)) << std::flush;
    }
    return 0;
  } catch (const rimu::InputError& e) {
    std::cerr << "rimu-colour: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "rimu-colour: internal error: " << e.what() << "\n";
    return 2;
  }
}
