// rimu-light: author lights in lumens, candela, lux or nits, inspect them, convert between units and recolour them
// at constant lumens. It declares the options and calls render/light_options.h, render/scene/light_definition.h and
// render/reports/ies_report.h (docs/light-units.md).
//
// Exit codes (common/tool_main.h): 0 ok, 1 bad input (the message names the file/option), 2 runtime failure
// (gnuplot missing, a write that failed).
#include <iostream>
#include <optional>

#include "common/tool_main.h"
#include "render/reports/ies_report.h"
#include "render/scene/ies_light_definition.h"
#include "render/scene/json_cursor.h"
#include "render/scene/light_definition.h"
#include "render/scene/spectrum_input.h"
#include "render/output/plot_output.h"
#include "render/light_options.h"
#include "render/output/output_file.h"
#include "render/output/text_file_output.h"
#include "spectral/error.h"

namespace {

using rimu::InputError;

struct Options {
  // Authoring: the top-level command.
  std::string type, output, plot, ies_file;
  rimu::LightAmountOptions amounts;
  rimu::SpotOptions spot;
  rimu::LightShapeOptions shape;
  // inspect
  CLI::App* inspect = nullptr;
  std::string inspect_file, inspect_plot, inspect_polar;
  std::optional<double> inspect_lumens;
  rimu::InspectPoint point;
  bool inspect_json = false;
  // convert
  CLI::App* convert = nullptr;
  rimu::ConvertRequest request;
  CLI::Option *convert_type = nullptr, *convert_cone = nullptr, *convert_area = nullptr, *convert_distance = nullptr;
  // recolor
  CLI::App* recolor = nullptr;
  std::string recolor_file, recolor_output;
  rimu::LightShapeOptions recolor_shape;
};

void add_shape_options(CLI::App& app, rimu::LightShapeOptions& shape) {
  app.add_option("--cct", shape.cct, "blackbody colour temperature, K (1000-25000; 2700 or 2700K)");
  app.add_option("--daylight", shape.daylight, "CIE daylight at a CCT, K (4000-25000; 6500 or 6500K)");
  app.add_option("--illuminant", shape.illuminant, "a CIE illuminant: D65, A, F11, LED-B3, ...");
  app.add_option("--csv", shape.csv, "a spectral power distribution: wavelength_nm, value");
}

void declare(CLI::App& app, Options& o) {
  app.add_option("--type", o.type, "point, spot, distant, environment, ies");
  app.add_option("--file", o.ies_file, "ies: the IES LM-63 photometric file (written as an absolute path)");
  app.add_option("--lumens", o.amounts.lumens,
                 "luminous power, lm (point, spot; ies: the luminaire's flux, the table scaled to it)");
  app.add_option("--candela", o.amounts.candela, "luminous intensity, cd (point, spot)");
  app.add_option("--lux", o.amounts.lux, "illuminance at normal incidence, lx (distant)");
  app.add_option("--nits", o.amounts.nits, "luminance, cd/m² (environment)");
  app.add_option("--watts", o.amounts.watts, "radiant power, W (point, spot)");
  app.add_option("--ev", o.amounts.ev, "exposure value at ISO 100 (distant: incident meter; environment: reflected meter)");
  app.add_option("--cone", o.spot.cone_deg, "spot: full cone angle, degrees (0.01-179.9, default 40)");
  app.add_option("--softness", o.spot.softness_deg, "spot: width of the soft edge, degrees (inside the cone)");
  app.add_option("--power-convention", o.spot.power_convention,
                 "spot lumens: cone (all inside the cone) or point (as if a point light)");
  app.add_option("-o,--output", o.output, "write the definition here (default: standard output)");
  app.add_option("--plot", o.plot, "also draw the spectral power distribution to this PNG (gnuplot)");
  add_shape_options(app, o.shape);

  o.inspect = app.add_subcommand("inspect", "everything about a light definition, a spectrum CSV or an IES file");
  o.inspect->add_option("file", o.inspect_file, "light definition (.json), spectrum (.csv) or IES photometric file (.ies)")
      ->required();
  o.inspect->add_option("--distance", o.point.distance_m, "for the illuminance of a point or spot light, m (default 1)");
  o.inspect->add_option("--angle", o.point.off_axis_deg, "off the spot's axis, degrees (default 0)");
  o.inspect->add_option("--electrical-watts", o.point.electrical_w, "the lamp's electrical power, W (source efficacy)");
  o.inspect->add_flag("--json", o.inspect_json, "print JSON instead of text");
  o.inspect->add_option("--plot", o.inspect_plot, "draw the spectral power distribution to this PNG (gnuplot)");
  o.inspect->add_option("--plot-polar", o.inspect_polar, "IES files: draw the candela distribution to this PNG (gnuplot)");
  o.inspect->add_option("--lumens", o.inspect_lumens,
                        "IES files: scale the table so the luminaire emits this many lm (candela, lux and plot follow)");

  rimu::ConvertRequest& r = o.request;
  o.convert = app.add_subcommand("convert", "convert an amount, e.g. --from \"1600 lm\" --to cd --type point; "
                                            "every value assumed by default is printed with the result");
  o.convert->add_option("--from", r.from, "amount and unit: \"1600 lm\", \"2 W/sr\", \"100 lx\", \"12 EV\"")->required();
  o.convert->add_option("--to", r.to, "unit: lm, W, cd, W/sr, lx, W/m2, nt, W/m2/sr, EV")->required();
  o.convert_type = o.convert->add_option("--type", r.type, "point (default), spot, distant, area, environment");
  o.convert_cone = o.convert->add_option("--cone", r.spot.cone_deg, "spot: full cone angle, degrees (default 40)");
  o.convert->add_option("--softness", r.spot.softness_deg, "spot: soft edge width, degrees (default 0)");
  o.convert->add_option("--power-convention", r.spot.power_convention, "spot: cone (default) or point");
  o.convert_area = o.convert->add_option("--area", r.area_m2, "area light: emitting area, m² (default 1)");
  o.convert->add_flag("--two-sided", r.two_sided, "area light: emits from both faces");
  o.convert_distance = o.convert->add_option("--distance", r.distance_m, "point/spot lux: distance on axis, m (default 1)");
  add_shape_options(*o.convert, r.shape);

  o.recolor = app.add_subcommand("recolor", "change a light's spectrum at constant lumens");
  o.recolor->add_option("file", o.recolor_file, "light definition (.json)")->required();
  o.recolor->add_option("-o,--output", o.recolor_output, "write here (default: standard output)");
  add_shape_options(*o.recolor, o.recolor_shape);
}

// A definition to standard output, or whole to a file (a failed write is reported, never half a file).
void write_text_output(const nlohmann::json& definition, const std::string& output) {
  const std::string text = definition.dump(2) + "\n";
  if (output.empty() || output == "-")
    std::cout << text;
  else
    rimu::write_text_file(output, text);
}

void write_definition(const rimu::LightDefinition& light, const std::string& output) {
  write_text_output(rimu::light_definition_json(light), output);
}

std::string json_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

// Refuses an output (a definition or a plot) that is one of the files the command reads.
void check_not_input(const std::string& output, const std::string& option, const std::vector<rimu::InputFile>& inputs) {
  if (!output.empty() && output != "-") rimu::check_output_not_input(output, option, inputs);
}

void inspect(const Options& o, rimu::SpectralLibrary& library, const std::filesystem::path& here) {
  // Every output path and every option is checked before anything is computed or written.
  rimu::validate_inspect_point(o.point);
  if (!o.inspect_plot.empty()) rimu::check_plot_png(o.inspect_plot, {"", 0, "--plot"});
  if (!o.inspect_polar.empty()) rimu::check_plot_png(o.inspect_polar, {"", 0, "--plot-polar"});
  check_not_input(o.inspect_plot, "--plot", {{o.inspect_file, "inspect"}});
  check_not_input(o.inspect_polar, "--plot-polar", {{o.inspect_file, "inspect"}});
  std::string extension = std::filesystem::path(o.inspect_file).extension().string();
  for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  // An IES file, or a definition of an ies light: the photometric report, and the polar curve for --plot-polar (or
  // --plot: an IES table has no spectrum of its own to draw).
  std::optional<nlohmann::json> document;
  if (extension != ".ies" && extension != ".csv") document = rimu::parse_json_file(o.inspect_file);
  if (extension == ".ies" || (document && rimu::is_ies_light_definition(*document))) {
    if (!o.inspect_plot.empty() && !o.inspect_polar.empty())
      throw InputError({"", 0, "--plot"}, "for an IES light --plot and --plot-polar both draw the polar curve; give one");
    const std::string polar = o.inspect_polar.empty() ? o.inspect_plot : o.inspect_polar;
    std::optional<double> lumens = o.inspect_lumens;
    rimu::IesPhotometry ies;
    if (document) {
      const rimu::IesLightDefinition light = rimu::read_ies_light_definition(*document, o.inspect_file);
      // Relative paths in a definition as for the other lights' CSV spectra: from the working folder (rimu-light
      // writes the IES file's path absolute).
      ies = rimu::validate_ies_light_definition(light, library, here, {o.inspect_file, 0, ""});
      if (!lumens) lumens = light.luminous_power_lm;
      if (!o.inspect_json) std::cout << "definition: " << o.inspect_file << ", spectrum " << light.spectrum.dump() << "\n";
    } else {
      ies = rimu::read_ies_file(o.inspect_file);
    }
    std::cout << (o.inspect_json ? json_text(rimu::inspect_ies_json(ies, o.point, lumens))
                                 : rimu::inspect_ies_text(ies, o.point, lumens));
    if (!polar.empty()) rimu::plot_ies_polar_png(ies, polar, lumens, o.inspect_polar.empty() ? "--plot" : "--plot-polar");
    return;
  }
  if (o.inspect_lumens)
    throw InputError({"", 0, "--lumens"}, "scales an IES light's table; for other lights give the amount in the definition");
  if (!o.inspect_polar.empty())
    throw InputError({"", 0, "--plot-polar"}, "a polar candela plot needs an IES file (.ies) or an ies light definition");
  rimu::LightDefinition light;
  if (extension == ".csv") {
    light.spectrum = {{"csv", std::filesystem::absolute(o.inspect_file).string()}};
    light.amount = {1.0, rimu::LightUnit::watt};  // the file's own scale: 1 W per unit of its integral
  } else {
    light = rimu::read_light_definition(*document, o.inspect_file);
  }
  rimu::validate_light_definition(light, library, here, {o.inspect_file, 0, ""});
  std::cout << (o.inspect_json ? json_text(rimu::inspect_light_json(light, library, here, o.point))
                               : rimu::inspect_light_text(light, library, here, o.point));
  if (!o.inspect_plot.empty()) {
    const rimu::SpectrumPtr s = rimu::light_shape(light, library, here);
    rimu::plot_spectrum_png(*s, 1.0 / s->max_value(), "relative spectral power", s->describe(), o.inspect_plot);
  }
}

// `--type ies`: the file, its flux (or the file's own candela) and a colour; the other amounts and the spot's cone
// do not apply to a measured table.
void author_ies(const Options& o, rimu::SpectralLibrary& library, const std::filesystem::path& here) {
  const rimu::LightAmountOptions& a = o.amounts;
  for (const auto& [given, flag] : {std::pair{a.candela.has_value(), "--candela"}, {a.lux.has_value(), "--lux"},
                                    {a.nits.has_value(), "--nits"}, {a.watts.has_value(), "--watts"},
                                    {a.ev.has_value(), "--ev"}})
    if (given)
      throw InputError({"", 0, flag}, "an ies light takes --lumens (the luminaire's flux) or no amount (the file's "
                                      "candela as they are)");
  const rimu::SpotOptions spot_defaults;
  if (o.spot.cone_deg != spot_defaults.cone_deg || o.spot.softness_deg != spot_defaults.softness_deg ||
      o.spot.power_convention != spot_defaults.power_convention)
    throw InputError({"", 0, "--cone"}, "an ies light's beam is its file's table: --cone, --softness and "
                                        "--power-convention do not apply");
  check_not_input(o.output, "-o", {{o.ies_file, "--file"}});
  check_not_input(o.plot, "--plot", {{o.ies_file, "--file"}});
  rimu::IesLightDefinition light;
  rimu::naming_shape_option(o.shape, [&] {
    light = rimu::ies_light_from_options(o.ies_file, a.lumens, o.shape.spectrum(), library, here);
  });
  write_text_output(rimu::ies_light_definition_json(light), o.output);
  if (!o.plot.empty()) {
    rimu::SpectrumInputContext spectra(library, here);
    const rimu::SpectrumPtr s = spectra.parse(rimu::JsonCursor(light.spectrum, "", "/spectrum"), rimu::SpectrumRole::emission);
    rimu::plot_spectrum_png(*s, 1.0 / s->max_value(), "relative spectral power", s->describe(), o.plot);
  }
}

void author(const Options& o, rimu::SpectralLibrary& library, const std::filesystem::path& here) {
  if (!o.output.empty() && o.output != "-") rimu::check_output_path(o.output);
  if (!o.plot.empty()) rimu::check_plot_png(o.plot, {"", 0, "--plot"});
  check_not_input(o.output, "-o", {{o.shape.csv, "--csv"}});
  check_not_input(o.plot, "--plot", {{o.shape.csv, "--csv"}});
  if (!o.output.empty() && !o.plot.empty() && rimu::same_output_file(o.output, o.plot))
    throw InputError({o.plot, 0, "--plot"}, "-o and --plot name the same file; the plot would replace the definition");
  if (o.type == "ies") return author_ies(o, library, here);
  if (!o.ies_file.empty()) throw InputError({"", 0, "--file"}, "an IES file makes an ies light: give --type ies");
  const rimu::LightDefinition light = rimu::light_from_options(o.type, o.spot, o.amounts, o.shape, library, here);
  write_definition(light, o.output);
  if (!o.plot.empty()) {
    const rimu::SpectrumPtr s = rimu::light_shape(light, library, here);
    rimu::plot_spectrum_png(*s, 1.0 / s->max_value(), "relative spectral power", s->describe(), o.plot);
  }
}

void run(Options& o) {
  rimu::SpectralLibrary library = rimu::SpectralLibrary::at_default_location();
  const std::filesystem::path here = std::filesystem::current_path();
  if (*o.inspect) return inspect(o, library, here);
  if (*o.convert) {
    o.request.type_given = o.convert_type->count() > 0;
    o.request.cone_given = o.convert_cone->count() > 0;
    o.request.area_given = o.convert_area->count() > 0;
    o.request.distance_given = o.convert_distance->count() > 0;
    std::cout << rimu::convert_light_text(o.request, library, here);
    return;
  }
  if (*o.recolor) {
    const auto s = o.recolor_shape.spectrum();
    if (!s) throw InputError({"", 0, "recolor"}, "give the new colour: --cct, --daylight, --illuminant or --csv");
    if (!o.recolor_output.empty() && o.recolor_output != "-") rimu::check_output_path(o.recolor_output);
    check_not_input(o.recolor_output, "-o", {{o.recolor_file, "recolor"}, {o.recolor_shape.csv, "--csv"}});
    const nlohmann::json document = rimu::parse_json_file(o.recolor_file);
    if (rimu::is_ies_light_definition(document)) {
      // Only the colour changes: a scene normalises an ies light's spectrum to one candela per table unit.
      const rimu::IesLightDefinition ies = rimu::read_ies_light_definition(document, o.recolor_file);
      check_not_input(o.recolor_output, "-o", {{rimu::ies_light_file(ies, here), "the definition's IES file"}});
      rimu::naming_shape_option(o.recolor_shape, [&] {
        write_text_output(rimu::ies_light_definition_json(rimu::recolor_ies_light(ies, *s, library, here)),
                          o.recolor_output);
      });
      return;
    }
    const rimu::LightDefinition light = rimu::read_light_definition(document, o.recolor_file);
    rimu::naming_shape_option(o.recolor_shape, [&] {
      write_definition(rimu::recolor_light(light, *s, library, here), o.recolor_output);
    });
    return;
  }
  author(o, library, here);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  return rimu::run_tool({"rimu-light", "rimu-light: lights in lm, cd, lx, nt, W or EV (docs/light-units.md)"}, argc,
                        argv, [&](CLI::App& app) { declare(app, options); }, [&] { run(options); });
}
