#include "render/light_options.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "spectral/error.h"
#include "spectral/photometry/light_units.h"

namespace rimu {

double parse_temperature_k(const std::string& text, const std::string& option) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double k = std::strtod(begin, &end);
  std::string rest(end);
  while (!rest.empty() && rest.front() == ' ') rest.erase(rest.begin());
  if (end == begin || !(rest.empty() || rest == "K" || rest == "k"))
    throw InputError({"", 0, option}, "expected a colour temperature in kelvin, e.g. 2700 or 2700K; got '" + text + "'");
  if (!std::isfinite(k)) throw InputError({"", 0, option}, "expected a finite colour temperature; got '" + text + "'");
  return k;
}

std::optional<nlohmann::json> LightShapeOptions::spectrum() const {
  const int given = !cct.empty() + !daylight.empty() + !illuminant.empty() + !csv.empty();
  if (given > 1)
    throw InputError({"", 0, given_option().substr(0, given_option().find(' '))},
                     "give one of --cct, --daylight, --illuminant, --csv");
  if (!cct.empty()) return cct_spectrum(parse_temperature_k(cct, "--cct"), false, {"", 0, "--cct"});
  if (!daylight.empty()) return cct_spectrum(parse_temperature_k(daylight, "--daylight"), true, {"", 0, "--daylight"});
  if (!illuminant.empty()) return nlohmann::json{{"illuminant", illuminant}};
  if (!csv.empty()) return nlohmann::json{{"csv", std::filesystem::absolute(csv).string()}};
  return std::nullopt;
}

std::string LightShapeOptions::given_option() const {
  if (!cct.empty()) return "--cct " + cct;
  if (!daylight.empty()) return "--daylight " + daylight;
  if (!illuminant.empty()) return "--illuminant " + illuminant;
  if (!csv.empty()) return "--csv " + csv;
  return "";
}

EmitterKind parse_light_type(const std::string& text, LightTypeUse use, const std::string& option) {
  if (text == "point") return EmitterKind::point;
  if (text == "spot") return EmitterKind::spot;
  if (text == "distant" || text == "sun") return EmitterKind::distant;
  if (text == "environment") return EmitterKind::environment;
  if (text == "area" && use == LightTypeUse::conversion) return EmitterKind::area;
  if (text == "area")
    throw InputError({"", 0, option}, "an area light has no definition file: it is a shape with an \"emission\" in a "
                                      "scene (docs/light-units.md); `rimu-light convert --type area` converts its units");
  throw InputError({"", 0, option}, "unknown light type '" + text + "'; expected point, spot, distant, " +
                                        (use == LightTypeUse::conversion ? "area, " : "") + "environment");
}

EmitterGeometry light_geometry(EmitterKind kind, const SpotOptions& spot, double area_m2, bool two_sided) {
  EmitterGeometry g;
  g.kind = kind;
  if (kind == EmitterKind::spot) {
    if (!(spot.cone_deg >= kMinConeAngleDeg && spot.cone_deg <= kMaxConeAngleDeg)) {
      std::ostringstream m;
      m << "the cone angle must be in [" << kMinConeAngleDeg << ", " << kMaxConeAngleDeg << "] degrees; got "
        << spot.cone_deg;
      throw InputError({"", 0, "--cone"}, m.str());
    }
    if (!(spot.softness_deg >= 0.0 && spot.softness_deg <= spot.cone_deg / 2.0))
      throw InputError({"", 0, "--softness"}, "the softness must be in [0, cone/2] degrees");
    g.outer_half_angle_deg = spot.cone_deg / 2.0;
    g.inner_half_angle_deg = spot.cone_deg / 2.0 - spot.softness_deg;
  }
  if (spot.power_convention != "cone" && spot.power_convention != "point")
    throw InputError({"", 0, "--power-convention"}, "expected cone or point; got '" + spot.power_convention + "'");
  g.spot_power = spot.power_convention == "cone" ? SpotPowerConvention::cone : SpotPowerConvention::point;
  if (kind == EmitterKind::area) {
    // 1e-12 m² (a square micrometre) to 1e12 m² keeps power / (π A) finite for every amount in range.
    if (!(area_m2 >= 1e-12 && area_m2 <= 1e12)) {
      std::ostringstream m;
      m << "the emitting area must be in [1e-12, 1e12] m²; got " << area_m2;
      throw InputError({"", 0, "--area"}, m.str());
    }
    g.area_m2 = area_m2;
    g.two_sided = two_sided;
  }
  return g;
}

void naming_shape_option(const LightShapeOptions& shape, const std::function<void()>& step) {
  try {
    step();
  } catch (const InputError& e) {
    // The options' spectrum is JSON without a file, or the CSV file they named (whose file and line are kept).
    const std::string option = shape.given_option();
    const SourceLocation& where = e.where();
    const bool from_options =
        where.file.empty() || (!shape.csv.empty() && where.file == std::filesystem::absolute(shape.csv).string());
    if (!option.empty() && from_options && where.key.rfind("/spectrum", 0) == 0)
      throw InputError({where.file, where.line, option.substr(0, option.find(' '))}, e.explanation());
    throw;
  }
}

LightAmount LightAmountOptions::amount() const {
  struct Flag {
    const std::optional<double>& value;
    LightUnit unit;
    const char* option;
  };
  const Flag flags[] = {{lumens, LightUnit::lumen, "--lumens"}, {candela, LightUnit::candela, "--candela"},
                        {lux, LightUnit::lux, "--lux"},          {nits, LightUnit::nit, "--nits"},
                        {watts, LightUnit::watt, "--watts"},     {ev, LightUnit::ev100, "--ev"}};
  int given = 0;
  LightAmount amount;
  for (const Flag& f : flags) {
    if (!f.value) continue;
    ++given;
    amount = {*f.value, f.unit};
    if (f.unit != LightUnit::ev100 && !(*f.value > 0.0))
      throw InputError({"", 0, f.option}, "the amount must be positive; got " + format_light_amount(amount));
    check_light_amount_range(amount, {"", 0, f.option});
  }
  if (given != 1)
    throw InputError({"", 0, "--lumens"}, "give exactly one of --lumens, --candela, --lux, --nits, --watts, --ev");
  return amount;
}

LightDefinition light_from_options(const std::string& type, const SpotOptions& spot, const LightAmountOptions& amounts,
                                   const LightShapeOptions& shape, SpectralLibrary& library,
                                   const std::filesystem::path& directory) {
  if (type.empty())
    throw InputError({"", 0, "--type"}, "give --type (point, spot, distant, environment) or a subcommand "
                                        "(inspect, convert, recolor); see --help");
  LightDefinition light;
  light.geometry = light_geometry(parse_light_type(type, LightTypeUse::definition, "--type"), spot, 0.0, false);
  light.amount = amounts.amount();
  const std::optional<nlohmann::json> spectrum = shape.spectrum();
  if (spectrum) light.spectrum = *spectrum;
  naming_shape_option(shape, [&] { validate_light_definition(light, library, directory, {"", 0, "amount"}); });
  return light;
}

namespace {

// What a unit measures on this kind of light: EV is a luminance (area, environment) or an illuminance (distant).
LightQuantity measured(LightUnit unit, EmitterKind kind) {
  if (unit != LightUnit::ev100) return quantity_of(unit);
  return kind == EmitterKind::distant ? LightQuantity::irradiance : LightQuantity::radiance;
}

}  // namespace

std::string convert_light_text(const ConvertRequest& request, SpectralLibrary& library,
                               const std::filesystem::path& directory) {
  if (!(request.distance_m > 0.0 && request.distance_m <= 1e15)) {
    std::ostringstream m;
    m << "expected a distance in (0, 1e15] m; got " << request.distance_m;
    throw InputError({"", 0, "--distance"}, m.str());
  }
  LightDefinition light;
  const EmitterKind kind = parse_light_type(request.type, LightTypeUse::conversion, "--type");
  light.geometry = light_geometry(kind, request.spot, request.area_m2, request.two_sided);
  light.amount = parse_light_amount(request.from, {"", 0, "--from"});
  const std::optional<nlohmann::json> shape = request.shape.spectrum();
  if (shape) light.spectrum = *shape;
  const LightUnit to = parse_light_unit(request.to, {"", 0, "--to"});
  double value = 0.0;
  naming_shape_option(request.shape, [&] {
    value = convert_light_amount(light, to, library, directory, request.distance_m, {"", 0, "--to"});
  });

  std::ostringstream out;
  out << format_light_amount(light.amount) << " = " << format_light_amount({value, to}) << "\n";
  // Every default the number above depends on, so that a silent 1 m or 40° cannot pass unnoticed.
  const bool geometry_matters = measured(light.amount.unit, kind) != measured(to, kind);
  const bool delta = kind == EmitterKind::point || kind == EmitterKind::spot;
  if (!request.type_given && geometry_matters) out << "assuming a point light (--type)\n";
  if (kind == EmitterKind::spot && geometry_matters && !request.cone_given) {
    out << "assuming a " << request.spot.cone_deg << "° cone";
    if (request.spot.softness_deg > 0.0)
      out << " soft over its outer " << request.spot.softness_deg << "°";
    else
      out << " with a hard edge";
    out << ", lumens counted " << (request.spot.power_convention == "cone" ? "over the cone" : "as for a point light")
        << " (--cone, --softness, --power-convention)\n";
  }
  if (kind == EmitterKind::area && geometry_matters && !request.area_given)
    out << "assuming " << request.area_m2 << " m² emitting from " << (request.two_sided ? "both faces" : "one face")
        << " (--area, --two-sided)\n";
  if (delta && !request.distance_given && (to == LightUnit::lux || to == LightUnit::watt_per_m2))
    out << "assuming a surface facing the light on its axis at " << request.distance_m << " m (--distance)\n";
  if (!shape && is_photometric(light.amount.unit) != is_photometric(to))
    out << "assuming the spectrum of illuminant E, equal energy (--cct, --daylight, --illuminant or --csv)\n";
  return out.str();
}

}  // namespace rimu
