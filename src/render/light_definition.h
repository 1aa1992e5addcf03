// A light definition as rimu-light writes it and a scene includes it ({"include": "lamp.json", "position": ...}):
// kind, spectral shape and one amount. The library side of `rimu-light` (author, inspect, convert, recolor, plot).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "spectral/emitter_photometry.h"
#include "spectral/spectral_library.h"
#include "spectral/spectrum.h"

namespace rimu {

struct LightDefinition {
  EmitterGeometry geometry;
  nlohmann::json spectrum = nlohmann::json{{"illuminant", "E"}};  ///< a scene spectral value (docs/scene-format.md)
  LightAmount amount{1000.0, LightUnit::lumen};
  std::string source;  ///< the file it was read from, for messages ("" when made from options)
};

/// The spectral value of a CCT: {"blackbody": T} (1000-25000 K) or {"daylight": T} (4000-25000 K, CIE daylight's
/// defined range). Throws InputError at `where` with the valid range.
nlohmann::json cct_spectrum(double cct_k, bool daylight, const SourceLocation& where);

/// Checks a definition: amount positive and of a unit the kind takes, cone 0 < falloff ≤ cone < 180°, the shape has
/// visible power. Throws InputError at `where`.
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
/// illuminance at `distance_m` and `off_axis_deg`, and the source efficacy if `electrical_w` is given.
std::string inspect_light_text(const LightDefinition& light, SpectralLibrary& library,
                               const std::filesystem::path& directory, double distance_m, double off_axis_deg,
                               std::optional<double> electrical_w);

/// A spectrum's description as a plot title: a CSV spectrum ("<path> [column]") shown by its file name.
std::string spectrum_plot_title(const std::string& description);

/// Draws scale × shape over 360-830 nm to a PNG (render/plot_output.h: gnuplot without a shell, $RIMU_GNUPLOT or
/// /usr/bin/gnuplot), titled spectrum_plot_title(title). Throws InputError if `png` cannot be written (checked
/// first), RenderError if gnuplot is missing or fails.
void plot_spectrum_png(const Spectrum& shape, double scale, const std::string& y_label, const std::string& title,
                       const std::filesystem::path& png);

}  // namespace rimu
