#include "render/scene/light_definition.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "render/scene/json_cursor.h"
#include "render/scene/light_amount_key.h"
#include "render/output/plot_output.h"
#include "spectral/error.h"
#include "render/scene/spectrum_input.h"
#include "spectral/reports/spectrum_report.h"

namespace rimu {
namespace {

// printf-style formatting of one number into a string of whatever length the format needs (a fixed buffer once
// cut the efficacy line of `rimu-light inspect` short).
std::string fmt(const char* format, double value) {
  const int length = std::snprintf(nullptr, 0, format, value);
  if (length <= 0) return {};
  std::string out(size_t(length) + 1, '\0');
  std::snprintf(out.data(), out.size(), format, value);
  out.pop_back();
  return out;
}

// The CSV file a light made from options takes its spectrum from ({"csv": path}), or "".
std::string spectrum_csv(const LightDefinition& light) {
  if (!light.source.empty() || !light.spectrum.is_object()) return "";
  const auto it = light.spectrum.find("csv");
  return it != light.spectrum.end() && it->is_string() ? it->get<std::string>() : "";
}

// A spectrum error of a light without a file of its own that comes from a CSV (--csv, inspect lamp.csv): the CSV
// is what the user named, so the error names it (with its line, if it has one) and not a JSON key of no file.
[[noreturn]] void rethrow_at_spectrum_origin(const LightDefinition& light, const InputError& e) {
  const std::string csv = spectrum_csv(light);
  if (csv.empty()) throw e;
  SourceLocation where = e.where();
  if (where.file.empty()) where = {csv, 0, ""};
  where.key.clear();
  throw InputError(where, e.explanation());
}

// A report value: one that is not finite (an overflow the input ranges did not prevent) is refused, never printed.
std::string report_fmt(const char* format, double value) {
  if (!std::isfinite(value))
    throw InputError({}, "a result overflows (" + std::string(format) + " of a value that is not a finite number); "
                         "the light's amount or the inspection options are too extreme");
  return fmt(format, value);
}

ShapeIntegrals integrals(const LightDefinition& light, SpectralLibrary& library, const std::filesystem::path& dir) {
  const SpectrumPtr shape = light_shape(light, library, dir);
  try {
    return shape_integrals(*shape, library.photopic_v());
  } catch (const InputError& e) {
    if (!light.source.empty()) throw InputError({light.source, 0, "/spectrum"}, e.explanation());
    rethrow_at_spectrum_origin(light, e);
  }
}

}  // namespace

nlohmann::json cct_spectrum(double cct_k, bool daylight, const SourceLocation& where) {
  const double lo = daylight ? 4000.0 : 1000.0;
  if (!(cct_k >= lo && cct_k <= 25000.0))
    throw InputError(where, std::string(daylight ? "a daylight" : "a blackbody") + " CCT must be in " +
                                (daylight ? "4000" : "1000") + "-25000 K; got " + fmt("%g", cct_k) + " K");
  return daylight ? nlohmann::json{{"daylight", cct_k}} : nlohmann::json{{"blackbody", cct_k}};
}

SpectrumPtr light_shape(const LightDefinition& light, SpectralLibrary& library, const std::filesystem::path& dir) {
  SpectrumInputContext context(library, dir);
  try {
    return context.parse(JsonCursor(light.spectrum, light.source, "/spectrum"),
                         SpectrumRole::emission);
  } catch (const InputError& e) {
    rethrow_at_spectrum_origin(light, e);
  }
}

void validate_light_definition(const LightDefinition& light, SpectralLibrary& library,
                               const std::filesystem::path& dir, const SourceLocation& where) {
  const EmitterGeometry& g = light.geometry;
  if (light.amount.unit != LightUnit::ev100 && !(light.amount.value > 0.0))
    throw InputError(where, "the amount must be positive; got " + format_light_amount(light.amount));
  check_light_amount_range(light.amount, where);
  // The same limits read_light_definition() applies, so that whatever passes here is read back.
  const double cone_deg = 2.0 * g.outer_half_angle_deg;
  if (g.kind == EmitterKind::spot && !(cone_deg >= kMinConeAngleDeg && cone_deg <= kMaxConeAngleDeg))
    throw InputError(where, "the cone angle must be in [" + fmt("%g", kMinConeAngleDeg) + ", " +
                                fmt("%g", kMaxConeAngleDeg) + "] degrees; got " + fmt("%g", cone_deg));
  if (g.kind == EmitterKind::spot && !(g.inner_half_angle_deg >= 0.0 && g.inner_half_angle_deg <= g.outer_half_angle_deg))
    throw InputError(where, "the softness must be between 0 and half the cone angle");
  try {
    shape_scale(light.amount, g, integrals(light, library, dir), where);
  } catch (const InputError& e) {
    if (!e.where().file.empty() || !e.where().key.empty()) throw;  // already says where (a CSV's line, a key)
    throw InputError(where, e.explanation());
  }
}

nlohmann::json light_definition_json(const LightDefinition& light) {
  nlohmann::ordered_json j;
  j["type"] = light.geometry.kind_name();
  j["spectrum"] = light.spectrum;
  for (const LightAmountKey& k : kLightAmountKeys)
    if (k.unit == light.amount.unit) j[k.key] = light.amount.value;
  if (light.geometry.kind == EmitterKind::spot) {
    j["cone_angle_deg"] = 2.0 * light.geometry.outer_half_angle_deg;
    j["falloff_start_deg"] = 2.0 * light.geometry.inner_half_angle_deg;
    j["power_convention"] = light.geometry.spot_power == SpotPowerConvention::cone ? "cone" : "point";
  }
  return nlohmann::json::parse(j.dump());
}

LightDefinition read_light_definition(const nlohmann::json& document, const std::string& file) {
  const JsonCursor root(document, file);
  LightDefinition light;
  light.source = file;
  const std::string type = root.at("type").choice({"point", "spot", "distant", "environment"});
  light.geometry.kind = type == "point" ? EmitterKind::point
                        : type == "spot" ? EmitterKind::spot
                        : type == "distant" ? EmitterKind::distant
                                            : EmitterKind::environment;
  if (light.geometry.kind == EmitterKind::spot) {
    light.geometry.outer_half_angle_deg = root.at("cone_angle_deg").number(kMinConeAngleDeg, kMaxConeAngleDeg) / 2.0;
    light.geometry.inner_half_angle_deg =
        root.number_or("falloff_start_deg", 2.0 * light.geometry.outer_half_angle_deg, 0.0, kMaxConeAngleDeg) / 2.0;
    if (light.geometry.inner_half_angle_deg > light.geometry.outer_half_angle_deg)
      root.at("falloff_start_deg").fail("the falloff must start inside the cone (at most cone_angle_deg)");
    if (root.has("power_convention") && root.at("power_convention").choice({"cone", "point"}) == "point")
      light.geometry.spot_power = SpotPowerConvention::point;
  }
  light.spectrum = root.at("spectrum").value();
  const std::optional<KeyedLightAmount> amount = read_light_amount(root);
  if (!amount) root.fail("no amount: expected luminous_power_lm, luminous_intensity_cd, illuminance_lx, luminance_nt, "
                         "ev100 or a radiometric twin");
  light.amount = amount->amount;
  return light;
}

double convert_light_amount(const LightDefinition& light, LightUnit to, SpectralLibrary& library,
                            const std::filesystem::path& dir, double distance_m, const SourceLocation& where) {
  const ShapeIntegrals s = integrals(light, library, dir);
  const EmitterOutput out = emitter_output(light.geometry, shape_scale(light.amount, light.geometry, s, where), s);
  const EmitterKind kind = light.geometry.kind;
  const bool delta = kind == EmitterKind::point || kind == EmitterKind::spot;
  double value = 0.0;
  switch (to) {
    case LightUnit::lumen: value = out.luminous_power_lm; break;
    case LightUnit::watt: value = out.radiant_power_w; break;
    case LightUnit::candela: value = out.luminous_intensity_cd; break;
    case LightUnit::watt_per_sr: value = out.radiant_intensity_w_sr; break;
    case LightUnit::lux: value = delta ? out.luminous_intensity_cd / (distance_m * distance_m) : out.illuminance_lx; break;
    case LightUnit::watt_per_m2: value = delta ? out.radiant_intensity_w_sr / (distance_m * distance_m) : out.irradiance_w_m2; break;
    case LightUnit::nit: value = out.luminance_nt; break;
    case LightUnit::watt_per_m2_sr: value = out.radiance_w_m2_sr; break;
    case LightUnit::ev100:
      if (kind != EmitterKind::distant && kind != EmitterKind::environment && kind != EmitterKind::area)
        throw InputError(where, "EV applies to distant, area and environment lights");
      if (!std::isfinite(out.ev100))
        throw InputError(where, "the result is not a finite EV: " + format_light_amount(light.amount) +
                                    " is out of the range a meter reads (check the amount and --area)");
      return out.ev100;
  }
  if (!(value > 0.0))
    throw InputError(where, std::string("a ") + light.geometry.kind_name() + " light has no " + unit_symbol(to) +
                                " value (it is not one of the quantities this kind of light has)");
  if (!std::isfinite(value))
    throw InputError(where, "the result overflows: " + format_light_amount(light.amount) + " is more than " +
                                unit_symbol(to) + " can express here (check the amount, --area and --distance)");
  return value;
}

LightDefinition recolor_light(const LightDefinition& light, nlohmann::json new_spectrum, SpectralLibrary& library,
                              const std::filesystem::path& dir) {
  LightDefinition out = light;
  if (!is_photometric(light.amount.unit)) {
    // Keep the lumens, not the watts: restate the amount photometrically with the old shape first.
    const LightUnit twin = unit_of(quantity_of(light.amount.unit), true);
    out.amount = {light.amount.value * integrals(light, library, dir).efficacy_lm_W(), twin};
  }
  out.spectrum = std::move(new_spectrum);
  out.source = "";  // the new spectrum comes from the caller, not from the light's file
  validate_light_definition(out, library, dir, {"", 0, "recolor"});
  return out;
}

namespace {

// Everything inspect reports about a light, computed once for the text and the JSON forms.
struct Inspection {
  SpectrumPtr shape;
  SpectrumReport report;
  EmitterOutput output;
  double illuminance_at_point_lx = 0.0;
};

Inspection inspect(const LightDefinition& light, SpectralLibrary& library, const std::filesystem::path& dir,
                   const InspectPoint& point) {
  validate_inspect_point(point);
  Inspection i;
  i.shape = light_shape(light, library, dir);
  const ShapeIntegrals s = shape_integrals(*i.shape, library.photopic_v());
  i.output = emitter_output(light.geometry, shape_scale(light.amount, light.geometry, s, {}), s);
  i.report = analyse_spectrum(*i.shape, i.shape->describe(), library);
  if (i.output.luminous_intensity_cd > 0.0)
    i.illuminance_at_point_lx = illuminance_at_lx(light.geometry, i.output, point.distance_m, point.off_axis_deg);
  return i;
}

}  // namespace

std::string inspect_light_text(const LightDefinition& light, SpectralLibrary& library, const std::filesystem::path& dir,
                               const InspectPoint& point) {
  const Inspection i = inspect(light, library, dir, point);
  const EmitterGeometry& g = light.geometry;
  const EmitterOutput& o = i.output;
  std::ostringstream out;
  out << "light              " << g.kind_name() << ", " << format_light_amount(light.amount);
  if (g.kind == EmitterKind::spot)
    out << ", cone " << 2.0 * g.outer_half_angle_deg << "° (full from " << 2.0 * g.inner_half_angle_deg << "°), lumens "
        << (g.spot_power == SpotPowerConvention::cone ? "over the cone" : "as if a point light");
  out << "\n";
  out << report_text(i.report);
  out << report_fmt("efficacy           %.2f lm/W of radiation as lights count watts (trapezoid over 360-830 nm)",
                    o.efficacy_lm_W);
  if (point.electrical_w && o.luminous_power_lm > 0.0)
    out << report_fmt(", %.2f lm/W of the source", o.luminous_power_lm / *point.electrical_w)
        << report_fmt(" (%.1f %% wall-plug efficiency)", 100.0 * o.radiant_power_w / *point.electrical_w);
  out << "\n";
  if (o.luminous_power_lm > 0.0)
    out << report_fmt("power              %.6g lm", o.luminous_power_lm)
        << report_fmt(" = %.6g W (radiant)\n", o.radiant_power_w);
  if (o.luminous_intensity_cd > 0.0) {
    out << report_fmt("peak intensity     %.6g cd", o.luminous_intensity_cd)
        << report_fmt(" = %.6g W/sr\n", o.radiant_intensity_w_sr);
    out << report_fmt("illuminance        %.6g lx", i.illuminance_at_point_lx) << report_fmt(" at %g m", point.distance_m)
        << report_fmt(", %g° off axis, on a surface facing the light\n", point.off_axis_deg);
  }
  if (o.illuminance_lx > 0.0)
    out << report_fmt("illuminance        %.6g lx", o.illuminance_lx)
        << report_fmt(" = %.6g W/m² at normal incidence", o.irradiance_w_m2)
        << report_fmt(" (EV %.2f at ISO 100, incident meter C = 250)\n", o.ev100)
        << report_fmt("white Lambertian   %.6g nt\n", o.illuminance_lx / 3.14159265358979);
  if (o.luminance_nt > 0.0)
    out << report_fmt("luminance          %.6g nt", o.luminance_nt)
        << report_fmt(" = %.6g W/(m²·sr)", o.radiance_w_m2_sr)
        << report_fmt(" (EV %.2f at ISO 100, reflected meter K = 12.5)\n", o.ev100);
  return out.str();
}

std::string spectrum_plot_title(const std::string& description) {
  // A CSV spectrum describes itself as "<path>" or "<path> [column]": keep the column, show the file by its name.
  const size_t column = !description.empty() && description.back() == ']' ? description.rfind(" [") : std::string::npos;
  const std::string source = description.substr(0, column);
  if (source.find('/') == std::string::npos) return description;
  return plot_file_name(source) + (column == std::string::npos ? "" : description.substr(column));
}

nlohmann::json inspect_light_json(const LightDefinition& light, SpectralLibrary& library,
                                  const std::filesystem::path& dir, const InspectPoint& point) {
  const Inspection i = inspect(light, library, dir, point);
  const EmitterOutput& o = i.output;
  nlohmann::ordered_json j;
  j["light"] = nlohmann::ordered_json::parse(light_definition_json(light).dump());
  j["spectrum_report"] = nlohmann::ordered_json::parse(report_json(i.report));
  // Only the quantities this kind of light has (the others are 0 in EmitterOutput), each checked finite.
  const auto put = [&](const char* key, double value) {
    report_fmt("%g", value);  // throws on an overflow, as the text form does
    j[key] = value;
  };
  put("efficacy_lm_w", o.efficacy_lm_W);
  if (point.electrical_w && o.luminous_power_lm > 0.0) {
    put("electrical_power_w", *point.electrical_w);
    put("source_efficacy_lm_w", o.luminous_power_lm / *point.electrical_w);
    put("wall_plug_efficiency", o.radiant_power_w / *point.electrical_w);
  }
  if (o.luminous_power_lm > 0.0) put("luminous_power_lm", o.luminous_power_lm), put("radiant_power_w", o.radiant_power_w);
  if (o.luminous_intensity_cd > 0.0) {
    put("luminous_intensity_cd", o.luminous_intensity_cd);
    put("radiant_intensity_w_sr", o.radiant_intensity_w_sr);
    put("distance_m", point.distance_m);
    put("off_axis_deg", point.off_axis_deg);
    put("illuminance_at_distance_lx", i.illuminance_at_point_lx);
  }
  if (o.illuminance_lx > 0.0) put("illuminance_lx", o.illuminance_lx), put("irradiance_w_m2", o.irradiance_w_m2);
  if (o.luminance_nt > 0.0) put("luminance_nt", o.luminance_nt), put("radiance_w_m2_sr", o.radiance_w_m2_sr);
  if (o.illuminance_lx > 0.0 || o.luminance_nt > 0.0) put("ev100", o.ev100);
  return nlohmann::json::parse(j.dump());
}

void plot_spectrum_png(const Spectrum& shape, double scale, const std::string& y_label, const std::string& title,
                       const std::filesystem::path& png) {
  check_plot_png(png, {"", 0, "--plot"});
  std::ostringstream data;
  for (int nm = 360; nm <= 830; ++nm) data << nm << ' ' << scale * shape.value(nm) << '\n';
  GnuplotJob job;
  job.terminal = "pngcairo size 800,500";
  job.data_files = {{"spectrum.dat", data.str()}};
  job.commands = "set xlabel 'wavelength (nm)'\nset ylabel " + gnuplot_text(y_label) + " noenhanced\nset title " +
                 gnuplot_text(spectrum_plot_title(title)) + " noenhanced\nset xrange [360:830]\nset grid\n"
                 "plot 'spectrum.dat' using 1:2 with lines lw 2 notitle";
  draw_plot_png(job, png);
}

}  // namespace rimu
