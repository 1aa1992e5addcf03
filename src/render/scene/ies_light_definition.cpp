#include "render/scene/ies_light_definition.h"

#include <cmath>
#include <sstream>

#include "render/scene/json_cursor.h"
#include "render/scene/spectrum_input.h"
#include "spectral/photometry/light_units.h"

namespace rimu {
namespace {

// The flux range a scene accepts for a lamp (scene_ies_light.cpp): beyond, single-precision radiance overflows.
constexpr double kMinLumens = 1e-30, kMaxLumens = 1e30;

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

bool is_ies_light_definition(const nlohmann::json& document) {
  return document.is_object() && document.contains("type") && document["type"] == "ies";
}

IesLightDefinition read_ies_light_definition(const nlohmann::json& document, const std::string& file) {
  const JsonCursor root(document, file);
  root.only_keys({"type", "file", "spectrum", "luminous_power_lm"});
  root.at("type").choice({"ies"});
  IesLightDefinition light;
  light.source = file;
  light.file = root.at("file").string();
  if (light.file.empty()) root.at("file").fail("names no IES file");
  light.spectrum = root.at("spectrum").value();
  if (const auto lm = root.find("luminous_power_lm")) light.luminous_power_lm = lm->number(kMinLumens, kMaxLumens);
  return light;
}

nlohmann::json ies_light_definition_json(const IesLightDefinition& light) {
  nlohmann::json j{{"type", "ies"}, {"file", light.file}, {"spectrum", light.spectrum}};
  if (light.luminous_power_lm) j["luminous_power_lm"] = *light.luminous_power_lm;
  return j;
}

std::filesystem::path ies_light_file(const IesLightDefinition& light, const std::filesystem::path& directory) {
  const std::filesystem::path file(light.file);
  return file.is_absolute() ? file : directory / file;
}

double ies_candela_scale(const IesPhotometry& ies, std::optional<double> lumens) {
  if (!lumens) return 1.0;
  return *lumens / candela_distribution(ies)->integral_sr();
}

IesPhotometry validate_ies_light_definition(const IesLightDefinition& light, SpectralLibrary& library,
                                            const std::filesystem::path& directory, const SourceLocation& where) {
  if (light.luminous_power_lm && !(*light.luminous_power_lm >= kMinLumens && *light.luminous_power_lm <= kMaxLumens))
    throw InputError(where, "the luminous flux must be in [1e-30, 1e30] lm; got " +
                                number_text(*light.luminous_power_lm));
  // The spectrum as a scene reads it, and a luminous integral a scene can normalise to 1 cd.
  SpectrumInputContext spectra(library, directory);
  const SpectrumPtr shape = spectra.parse(JsonCursor(light.spectrum, light.source, "/spectrum"), SpectrumRole::emission);
  const ShapeIntegrals integrals = shape_integrals(*shape, library.photopic_v());
  if (!(integrals.luminous > 0.0) || !std::isfinite(1.0 / integrals.luminous))
    throw InputError({light.source, 0, "/spectrum"}, "the spectrum has no visible power (luminous integral " +
                                                         number_text(integrals.luminous) + "): an IES light needs it");
  const IesPhotometry ies = read_ies_file(ies_light_file(light, directory));
  const double table_lm = candela_distribution(ies)->integral_sr();
  if (!(table_lm > 0.0)) throw InputError({ies.name, 0, ""}, "the candela table is all zero: the light emits nothing");
  const double lumens = light.luminous_power_lm.value_or(table_lm);
  if (!std::isfinite(lumens / table_lm) || !(lumens <= kMaxLumens))
    throw InputError(where, "the IES table (" + number_text(table_lm) + " lm) cannot be scaled to " +
                                number_text(lumens) + " lm");
  return ies;
}

IesLightDefinition ies_light_from_options(const std::string& file, std::optional<double> lumens,
                                          std::optional<nlohmann::json> spectrum, SpectralLibrary& library,
                                          const std::filesystem::path& directory) {
  if (file.empty()) throw InputError({"", 0, "--file"}, "an ies light needs --file: the IES LM-63 photometric file");
  IesLightDefinition light;
  light.file = std::filesystem::absolute(directory / file).lexically_normal().string();
  light.luminous_power_lm = lumens;
  if (spectrum) light.spectrum = *spectrum;
  if (lumens && !(*lumens >= kMinLumens && *lumens <= kMaxLumens))
    throw InputError({"", 0, "--lumens"}, "expected a luminous flux in [1e-30, 1e30] lm; got " + number_text(*lumens));
  try {
    validate_ies_light_definition(light, library, directory, {"", 0, "--lumens"});
  } catch (const InputError& e) {
    // A bad IES file is named by its own path and line; anything else about the file is --file's.
    if (e.where().file.empty() && e.where().key.empty()) throw InputError({"", 0, "--file"}, e.explanation());
    throw;
  }
  return light;
}

IesLightDefinition recolor_ies_light(IesLightDefinition light, nlohmann::json spectrum, SpectralLibrary& library,
                                     const std::filesystem::path& directory) {
  light.spectrum = std::move(spectrum);
  const std::string source = light.source;
  light.source = "";  // the new spectrum comes from the caller, not from the light's file
  validate_ies_light_definition(light, library, directory, {source, 0, "recolor"});
  return light;
}

}  // namespace rimu
