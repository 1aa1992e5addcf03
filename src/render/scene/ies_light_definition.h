// An IES light as `rimu-light --type ies` writes it and a scene includes it ({"include": "downlight.json",
// "position": ..., "direction": ...}):
//
//   {"type": "ies", "file": "/abs/path/downlight.ies", "spectrum": {"blackbody": 3000}, "luminous_power_lm": 800}
//
// The file is written as an absolute path: a scene resolves a light's "file" from the scene's folder, and a
// definition is included by scenes anywhere. The candela table keeps its shape; "luminous_power_lm" scales it so
// that the luminaire emits that flux in all (∫ I dω over the bilinear table, render/scene/ies_file.h), without it
// the file's candela are taken as they are. The spectrum is only the colour: a scene normalises it so one table
// unit is one candela (render/scene/scene_ies_light.h), so a recoloured IES light keeps its lumens exactly.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "render/scene/ies_file.h"
#include "spectral/error.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

struct IesLightDefinition {
  std::string file;                                               ///< as written ("file"); absolute when authored
  nlohmann::json spectrum = nlohmann::json{{"illuminant", "E"}};  ///< a scene spectral value (docs/scene-format.md)
  std::optional<double> luminous_power_lm;                        ///< none: the file's candela as they are
  std::string source;                                             ///< the definition file, for messages ("" if none)
};

/// A definition document of "type": "ies" (the other types are read by read_light_definition()).
bool is_ies_light_definition(const nlohmann::json& document);

/// Reads a definition (keys type, file, spectrum, luminous_power_lm; InputError naming `file` and the key otherwise).
IesLightDefinition read_ies_light_definition(const nlohmann::json& document, const std::string& file);

/// {"type": "ies", "file", "spectrum", "luminous_power_lm"} (the last only when set).
nlohmann::json ies_light_definition_json(const IesLightDefinition& light);

/// The IES file of a definition: a relative "file" from `directory`.
std::filesystem::path ies_light_file(const IesLightDefinition& light, const std::filesystem::path& directory);

/// Reads the IES file and checks the definition as a scene would load it: the spectrum has visible power, the
/// lumens lie in [1e-30, 1e30], the table is not all zero and its scaled flux is finite. Returns the photometry.
/// Throws InputError at `where` (for a bad IES file: its name and line).
IesPhotometry validate_ies_light_definition(const IesLightDefinition& light, SpectralLibrary& library,
                                            const std::filesystem::path& directory, const SourceLocation& where);

/// The factor on the file's candela values that gives `lumens` in all (1 without): lumens / ∫ I dω.
double ies_candela_scale(const IesPhotometry& ies, std::optional<double> lumens);

/// `rimu-light --type ies --file x.ies [--lumens 800] [--cct ...]`: the definition, validated, with the file made
/// absolute. InputError naming --file, --lumens or the colour option at fault.
IesLightDefinition ies_light_from_options(const std::string& file, std::optional<double> lumens,
                                          std::optional<nlohmann::json> spectrum, SpectralLibrary& library,
                                          const std::filesystem::path& directory);

/// The same light in a new colour: only the spectrum changes, so the lumens (or the file's candela) stay.
IesLightDefinition recolor_ies_light(IesLightDefinition light, nlohmann::json spectrum, SpectralLibrary& library,
                                     const std::filesystem::path& directory);

}  // namespace rimu
