// rimu-light: author lights in lumens, candela, lux or nits, inspect them, convert between units and recolour them
// at constant lumens. It parses options and calls render/light_definition.h (docs/light-units.md).
//
// Exit codes: 0 ok, 1 bad input (the message names the file/option), 2 runtime failure (e.g. gnuplot missing).
#include <CLI/CLI.hpp>

#include <cctype>
#include <fstream>
#include <iostream>
#include <optional>

#include "render/ies_report.h"
#include "render/json_cursor.h"
#include "render/light_definition.h"
#include "render/plot_output.h"
#include "render/render_error.h"
#include "spectral/error.h"

namespace {

using rimu::InputError;

// The light's spectral shape from the flags: --cct (blackbody), --daylight, --illuminant or --csv.
struct ShapeFlags {
  double cct_k = 0, daylight_k = 0;
  std::string illuminant, csv;
  int given() const { return (cct_k != 0) + (daylight_k != 0) + !illuminant.empty() + !csv.empty(); }
  std::optional<nlohmann::json> spectrum() const {
    if (given() > 1) throw InputError({"", 0, "--cct"}, "give one of --cct, --daylight, --illuminant, --csv");
    if (cct_k != 0) return rimu::cct_spectrum(cct_k, false, {"", 0, "--cct"});
    if (daylight_k != 0) return rimu::cct_spectrum(daylight_k, true, {"", 0, "--daylight"});
    if (!illuminant.empty()) return nlohmann::json{{"illuminant", illuminant}};
    if (!csv.empty()) return nlohmann::json{{"csv", std::filesystem::absolute(csv).string()}};
    return std::nullopt;
  }
  void add_to(CLI::App& app) {
    app.add_option("--cct", cct_k, "blackbody colour temperature, K (1000-25000)");
    app.add_option("--daylight", daylight_k, "CIE daylight at a CCT, K (4000-25000)");
    app.add_option("--illuminant", illuminant, "a CIE illuminant: D65, A, F11, LED-B3, ...");
    app.add_option("--csv", csv, "a spectral power distribution: wavelength_nm, value");
  }
};

rimu::EmitterKind kind_of(const std::string& type) {
  if (type == "point") return rimu::EmitterKind::point;
  if (type == "spot") return rimu::EmitterKind::spot;
  if (type == "distant" || type == "sun") return rimu::EmitterKind::distant;
  if (type == "area") return rimu::EmitterKind::area;
  if (type == "environment") return rimu::EmitterKind::environment;
  throw InputError({"", 0, "--type"}, "unknown light type '" + type + "'; expected point, spot, distant, area, environment");
}

rimu::LightDefinition read_definition(const std::string& path) {
  return rimu::read_light_definition(rimu::parse_json_file(path), path);
}

void write_definition(const rimu::LightDefinition& light, const std::string& output) {
  const std::string text = rimu::light_definition_json(light).dump(2) + "\n";
  if (output.empty() || output == "-") {
    std::cout << text;
    return;
  }
  std::ofstream out(output);
  if (!(out << text)) throw InputError({output, 0, "-o"}, "cannot write the light definition");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rimu-light: lights in lm, cd, lx, nt, W or EV (docs/light-units.md)"};
  rimu::SpectralLibrary library = rimu::SpectralLibrary::at_default_location();
  const std::filesystem::path here = std::filesystem::current_path();

  // Authoring: the top-level command.
  std::string type, output, plot;
  std::optional<double> lumens, candela, lux, nits, watts, ev;
  double cone_deg = 40, softness_deg = 0;
  std::string power_convention = "cone";
  ShapeFlags shape;
  app.add_option("--type", type, "point, spot, distant, environment");
  app.add_option("--lumens", lumens, "luminous power, lm (point, spot)");
  app.add_option("--candela", candela, "luminous intensity, cd (point, spot)");
  app.add_option("--lux", lux, "illuminance at normal incidence, lx (distant)");
  app.add_option("--nits", nits, "luminance, cd/m² (environment)");
  app.add_option("--watts", watts, "radiant power, W (point, spot)");
  app.add_option("--ev", ev, "exposure value at ISO 100 (distant: incident meter; environment: reflected meter)");
  app.add_option("--cone", cone_deg, "spot: full cone angle, degrees");
  app.add_option("--softness", softness_deg, "spot: width of the soft edge, degrees (inside the cone)");
  app.add_option("--power-convention", power_convention, "spot lumens: cone (all inside the cone) or point (as if a point light)");
  app.add_option("-o,--output", output, "write the definition here (default: standard output)");
  app.add_option("--plot", plot, "also draw the spectral power distribution to this PNG (gnuplot)");
  shape.add_to(app);

  CLI::App* inspect = app.add_subcommand("inspect", "everything about a light definition or a spectrum CSV");
  std::string inspect_file;
  double distance_m = 1.0, angle_deg = 0.0;
  std::optional<double> electrical_w;
  std::string inspect_plot;
  inspect->add_option("file", inspect_file, "light definition (.json), spectrum (.csv) or IES photometric file (.ies)")->required();
  inspect->add_option("--distance", distance_m, "for the illuminance of a point or spot light, m");
  inspect->add_option("--angle", angle_deg, "off the spot's axis, degrees");
  inspect->add_option("--electrical-watts", electrical_w, "the lamp's electrical power, W (source efficacy)");
  inspect->add_option("--plot", inspect_plot, "draw the spectral power distribution to this PNG (gnuplot)");
  std::string inspect_polar;
  inspect->add_option("--plot-polar", inspect_polar, "IES files: draw the candela distribution to this PNG (gnuplot)");

  CLI::App* convert = app.add_subcommand("convert", "convert an amount, e.g. --from \"1600 lm\" --to cd --type point");
  std::string from, to, convert_type = "point";
  double convert_cone = 40, convert_softness = 0, area_m2 = 1.0, convert_distance = 1.0;
  bool two_sided = false;
  ShapeFlags convert_shape;
  convert->add_option("--from", from, "amount and unit: \"1600 lm\", \"2 W/sr\", \"100 lx\", \"12 EV\"")->required();
  convert->add_option("--to", to, "unit: lm, W, cd, W/sr, lx, W/m2, nt, W/m2/sr, EV")->required();
  convert->add_option("--type", convert_type, "point, spot, distant, area, environment");
  convert->add_option("--cone", convert_cone, "spot: full cone angle, degrees");
  convert->add_option("--softness", convert_softness, "spot: soft edge width, degrees");
  convert->add_option("--power-convention", power_convention, "spot: cone or point");
  convert->add_option("--area", area_m2, "area light: emitting area, m²");
  convert->add_flag("--two-sided", two_sided, "area light: emits from both faces");
  convert->add_option("--distance", convert_distance, "point/spot lux: distance on axis, m");
  convert_shape.add_to(*convert);

  CLI::App* recolor = app.add_subcommand("recolor", "change a light's spectrum at constant lumens");
  std::string recolor_file, recolor_output;
  ShapeFlags recolor_shape;
  recolor->add_option("file", recolor_file, "light definition (.json)")->required();
  recolor->add_option("-o,--output", recolor_output, "write here (default: standard output)");
  recolor_shape.add_to(*recolor);

  CLI11_PARSE(app, argc, argv);
  try {
    // A plot that cannot be drawn is refused before anything is printed or written.
    for (const auto& [png, key] : {std::pair{plot, "--plot"}, {inspect_plot, "--plot"}, {inspect_polar, "--plot-polar"}})
      if (!png.empty()) rimu::check_plot_png(png, {"", 0, key});
    const auto geometry_from = [&](const std::string& t, double cone, double soft) {
      rimu::EmitterGeometry g;
      g.kind = kind_of(t);
      g.outer_half_angle_deg = cone / 2.0;
      g.inner_half_angle_deg = cone / 2.0 - soft;
      if (g.kind == rimu::EmitterKind::spot && !(cone > 0.0 && cone < 180.0))
        throw InputError({"", 0, "--cone"}, "the cone angle must be in (0, 180) degrees; got " + std::to_string(cone));
      if (g.kind == rimu::EmitterKind::spot && !(soft >= 0.0 && soft <= cone / 2.0))
        throw InputError({"", 0, "--softness"}, "the softness must be in [0, cone/2] degrees");
      if (power_convention != "cone" && power_convention != "point")
        throw InputError({"", 0, "--power-convention"}, "expected cone or point");
      g.spot_power = power_convention == "cone" ? rimu::SpotPowerConvention::cone : rimu::SpotPowerConvention::point;
      return g;
    };
    if (*inspect) {
      std::string extension = std::filesystem::path(inspect_file).extension().string();
      for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
      if (extension == ".ies") {
        const rimu::IesPhotometry ies = rimu::read_ies_file(inspect_file);
        std::cout << rimu::inspect_ies_text(ies, distance_m, angle_deg, electrical_w);
        if (!inspect_polar.empty()) rimu::plot_ies_polar_png(ies, inspect_polar);
        return 0;
      }
      if (!inspect_polar.empty())
        throw InputError({"", 0, "--plot-polar"}, "a polar candela plot needs an IES file (.ies)");
      rimu::LightDefinition light;
      if (std::filesystem::path(inspect_file).extension() == ".csv") {
        light.spectrum = {{"csv", std::filesystem::absolute(inspect_file).string()}};
        light.amount = {1.0, rimu::LightUnit::watt};  // the file's own scale: 1 W per unit of its integral
      } else {
        light = read_definition(inspect_file);
      }
      rimu::validate_light_definition(light, library, here, {inspect_file, 0, ""});
      std::cout << rimu::inspect_light_text(light, library, here, distance_m, angle_deg, electrical_w);
      if (!inspect_plot.empty()) {
        const rimu::SpectrumPtr s = rimu::light_shape(light, library, here);
        rimu::plot_spectrum_png(*s, 1.0 / s->max_value(), "relative spectral power", s->describe(), inspect_plot);
      }
      return 0;
    }
    if (*convert) {
      rimu::LightDefinition light;
      light.geometry = geometry_from(convert_type, convert_cone, convert_softness);
      light.geometry.area_m2 = area_m2;
      light.geometry.two_sided = two_sided;
      light.amount = rimu::parse_light_amount(from, {"", 0, "--from"});
      if (auto s = convert_shape.spectrum()) light.spectrum = *s;
      const rimu::LightUnit unit = rimu::parse_light_unit(to, {"", 0, "--to"});
      const double value = rimu::convert_light_amount(light, unit, library, here, convert_distance, {"", 0, "--to"});
      std::cout << rimu::format_light_amount(light.amount) << " = " << rimu::format_light_amount({value, unit}) << "\n";
      return 0;
    }
    if (*recolor) {
      const auto s = recolor_shape.spectrum();
      if (!s) throw InputError({"", 0, "recolor"}, "give the new colour: --cct, --daylight, --illuminant or --csv");
      write_definition(rimu::recolor_light(read_definition(recolor_file), *s, library, here), recolor_output);
      return 0;
    }
    if (type.empty()) throw InputError({"", 0, "--type"}, "give --type (point, spot, distant, environment) or a subcommand");
    rimu::LightDefinition light;
    light.geometry = geometry_from(type, cone_deg, softness_deg);
    if (light.geometry.kind == rimu::EmitterKind::area)
      throw InputError({"", 0, "--type"}, "area lights are shapes with an \"emission\"; see docs/light-units.md");
    int amounts = 0;
    for (auto [v, u] : {std::pair{lumens, rimu::LightUnit::lumen}, {candela, rimu::LightUnit::candela},
                        {lux, rimu::LightUnit::lux}, {nits, rimu::LightUnit::nit}, {watts, rimu::LightUnit::watt},
                        {ev, rimu::LightUnit::ev100}})
      if (v) light.amount = {*v, u}, ++amounts;
    if (amounts != 1) throw InputError({"", 0, "--lumens"}, "give exactly one of --lumens, --candela, --lux, --nits, --watts, --ev");
    if (auto s = shape.spectrum()) light.spectrum = *s;
    rimu::validate_light_definition(light, library, here, {"", 0, "amount"});
    write_definition(light, output);
    if (!plot.empty()) {
      const rimu::SpectrumPtr s = rimu::light_shape(light, library, here);
      rimu::plot_spectrum_png(*s, 1.0 / s->max_value(), "relative spectral power", s->describe(), plot);
    }
    return 0;
  } catch (const InputError& e) {
    std::cerr << "rimu-light: " << e.what() << "\n";
    return 1;
  } catch (const rimu::RenderError& e) {
    std::cerr << "rimu-light: " << e.what() << "\n";
    return 2;
  }
}
