// A light definition as rimu-light writes it and a scene includes it ({"include": "lamp.json", "position": ...}):
// kind, spectral shape and one amount. The library side of `rimu-light` (author, inspect, convert, recolor, plot).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "render/scene/inspect_point.h"
#include "spectral/photometry/emitter_photometry.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

/// The full cone angle a spot light may have, in degrees, wherever it is given (definition files, rimu-light).
inline constexpr double kMinConeAngleDeg = 0.01;
inline constexpr double kMaxConeAngleDeg = 179.9;

struct LightDefinition {
  EmitterGeometry geometry;
  nlohmann::json spectrum = nlohmann::json{{"illuminant", "E"}};  ///< a scene spectral value (docs/scene-format.md)
  LightAmount amount{1000.0, LightUnit::lumen};
  std::string source;  ///< the file it was read from, for messages ("" when made from options)
};

/// The spectral value of a CCT: {"blackbody": T} (1000-25000 K) or {"daylight": T} (4000-25000 K, CIE daylight's
/// defined range). Throws InputError at `where` with the valid range.
nlohmann::json cct_spectrum(double cct_k, bool daylight, const SourceLocation& where);

/// Checks a definition: amount in check_light_amount_range() and of a unit the kind takes, cone in
/// [kMinConeAngleDeg, kMaxConeAngleDeg] with 0 ≤ falloff ≤ cone, the shape has visible power. Everything that passes
/// is written by light_definition_json() in a form read_light_definition() reads back unchanged.
/// Throws InputError at `where`.
void validate_light_definition(const LightDefinition& light, SpectralLibrary& library,
                               const std::filesystem::path& directory, const SourceLocation& where);

/// The JSON a scene can include: {"type", "spectrum", <amount key>, "cone_angle_deg", "falloff_start_deg",
/// "power_convention"}.
nlohmann::json light_definition_json(const LightDefinition& light);
/// Reads a definition (as written above, or any scene light in the photometric form). Errors name `file` and the key.
LightDefinition read_light_definition(const nlohmann::json& document, const std::string& file);

/// The shape, built like a scene builds it (CSV paths relative to `directory`).
SpectrumPtr light_shape(const LightDefinition& light, SpectralLibrary& library, const std::filesystem::path& directory);

/// `from` (on `light`'s geometry and shape) in `to`. Lux for a point or spot light is on axis at `distance_m`.
/// Throws InputError at `where` when `to` does not apply to the kind.
double convert_light_amount(const LightDefinition& light, LightUnit to, SpectralLibrary& library,
                            const std::filesystem::path& directory, double distance_m, const SourceLocation& where);

/// The same light with a new shape at the same photometric amount (a radiometric amount is first turned into its
/// photometric twin with the old shape, so the lumens are what stays).
LightDefinition recolor_light(const LightDefinition& light, nlohmann::json new_spectrum, SpectralLibrary& library,
                              const std::filesystem::path& directory);

/// What rimu-light inspect prints: the spectrum report (xy, u'v', CCT/Duv, CRI), the light in every unit, the
/// illuminance at the point's distance and angle, and the source efficacy if the electrical power is given.
/// Throws InputError if the point is invalid or a result overflows (no NaN or infinity is ever printed).
std::string inspect_light_text(const LightDefinition& light, SpectralLibrary& library,
                               const std::filesystem::path& directory, const InspectPoint& point);
/// The same as a JSON object: "light" (type, amount, unit, spectrum), "spectrum_report" (as rimu-colour report
/// --json), and every quantity of the light with its unit in the key.
nlohmann::json inspect_light_json(const LightDefinition& light, SpectralLibrary& library,
                                  const std::filesystem::path& directory, const InspectPoint& point);

/// A spectrum's description as a plot title: a CSV spectrum ("<path> [column]") shown by its file name.
std::string spectrum_plot_title(const std::string& description);

/// Draws scale × shape over 360-830 nm to a PNG (render/output/plot_output.h: gnuplot without a shell, $RIMU_GNUPLOT or
/// /usr/bin/gnuplot), titled spectrum_plot_title(title). Throws InputError if `png` cannot be written (checked
/// first), RenderError if gnuplot is missing or fails.
void plot_spectrum_png(const Spectrum& shape, double scale, const std::string& y_label, const std::string& title,
                       const std::filesystem::path& png);

}  // namespace rimu
