// rimu-light's command-line options as a library: the spectral shape flags, the light type and geometry, and the
// `convert` request with every assumption it makes spelled out. The tool only declares the options and calls these.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "render/scene/light_definition.h"

namespace rimu {

/// A colour temperature as a user types it: "2700", "2700K" or "2700 K" (as rimu --white-balance takes it).
/// Throws InputError at `option` for anything else; the range is checked by cct_spectrum().
double parse_temperature_k(const std::string& text, const std::string& option);

/// The light's spectral shape: at most one of --cct, --daylight, --illuminant, --csv (the strings as typed).
struct LightShapeOptions {
  std::string cct, daylight, illuminant, csv;
  /// The scene spectral value, or nullopt when none is given. Throws InputError for two at once or a bad value.
  std::optional<nlohmann::json> spectrum() const;
  /// "--cct 2700" etc. for the one given, or "" when none is.
  std::string given_option() const;
};

/// Runs `step` on a light whose spectrum came from `shape` (its origin ""): an InputError about the spectrum
/// ("/spectrum/illuminant: unknown illuminant") is raised again naming the option that gave it (--illuminant).
void naming_shape_option(const LightShapeOptions& shape, const std::function<void()>& step);

/// Which light types a command accepts: a definition file (point, spot, distant, environment; an area light is a
/// shape with an "emission" in a scene, so it has no definition file) or a unit conversion (all five).
enum class LightTypeUse { definition, conversion };
/// "point", "spot", "distant" (or "sun"), "area", "environment", as `use` allows. Throws InputError at `option`
/// listing exactly the types `use` accepts.
EmitterKind parse_light_type(const std::string& text, LightTypeUse use, const std::string& option);

/// A spot light's cone and its soft edge, and how its lumens are counted.
struct SpotOptions {
  double cone_deg = 40.0, softness_deg = 0.0;
  std::string power_convention = "cone";
};
/// The geometry of `kind` with the spot options (checked against the definition file's limits, naming --cone,
/// --softness or --power-convention) and, for an area light, the area and sidedness.
EmitterGeometry light_geometry(EmitterKind kind, const SpotOptions& spot, double area_m2, bool two_sided);

/// The amount flags of `rimu-light --type ...`: exactly one must be given.
struct LightAmountOptions {
  std::optional<double> lumens, candela, lux, nits, watts, ev;
  /// The one given, checked against check_light_amount_range() (NaN and infinity refused), naming its option.
  LightAmount amount() const;
};

/// `rimu-light --type ...`: the definition the options describe, validated (validate_light_definition()), so that
/// light_definition_json() of it is read back unchanged by read_light_definition(). Throws InputError naming the
/// option at fault.
LightDefinition light_from_options(const std::string& type, const SpotOptions& spot, const LightAmountOptions& amounts,
                                   const LightShapeOptions& shape, SpectralLibrary& library,
                                   const std::filesystem::path& directory);

/// `rimu-light convert`: an amount on a light, to a unit; which options the user gave, so that every value the
/// answer depends on but the user did not give is printed as an assumption.
struct ConvertRequest {
  std::string from, to;
  std::string type = "point";
  SpotOptions spot;
  double area_m2 = 1.0, distance_m = 1.0;
  bool two_sided = false;
  LightShapeOptions shape;
  bool type_given = false, cone_given = false, area_given = false, distance_given = false;
};
/// "1600 lm = 127.324 cd", then one "assuming ..." line per default the result depends on (the light type, the
/// spot cone, the area, the distance, the spectrum). Throws InputError naming the option at fault, also when the
/// result overflows.
std::string convert_light_text(const ConvertRequest& request, SpectralLibrary& library,
                               const std::filesystem::path& directory);

}  // namespace rimu
