// How much light a scene's light gives: an absolute spectrum (the radiometric form), or a spectral shape and one
// photometric or radiometric amount (docs/light-units.md). Internal to scene loading.
//
//   "intensity": {"blackbody": 2700, "scale": 3}              absolute: W/(sr·nm) as written (the original form)
//   "spectrum": {"blackbody": 2700}, "luminous_power_lm": 800  a shape, scaled once here so the light has 800 lm
//
// Amount keys: luminous_power_lm, radiant_power_w, luminous_intensity_cd, radiant_intensity_w_sr, illuminance_lx,
// irradiance_w_m2, luminance_nt, radiance_w_m2_sr, ev100 (which apply depends on the light; emitter_photometry.h).
// Optional: "keep": "photometric" (default) | "radiometric" with "reference_spectrum" (the shape the amount was
// authored for: the watts it had then are kept); spot lights: "power_convention": "cone" (default) | "point".
#pragma once

#include <initializer_list>

#include "render/scene/scene_load_context.h"
#include "spectral/photometry/emitter_photometry.h"
#include "transport/lights/light_spectrum.h"

namespace rimu::scene_loading {

/// True if `object` has any amount key (the photometric form).
bool has_light_amount(const JsonCursor& object);

/// Rejects keys other than `own` and the photometric form's keys (spectrum, the amount keys, keep,
/// reference_spectrum, power_convention).
void only_light_keys(const JsonCursor& object, std::initializer_list<const char*> own);

/// The spot power convention of `light` ("power_convention"; cone by default).
SpotPowerConvention spot_power_convention(const JsonCursor& light);

/// The light's spectrum: with an amount key, "spectrum" scaled through `geometry` (exactly one amount allowed;
/// `legacy_key` must then be absent); otherwise the absolute spectral value under `legacy_key`. Errors name the
/// key path.
LightSpectrum parse_light_emission(const JsonCursor& object, const char* legacy_key, const EmitterGeometry& geometry,
                                   LoadContext& context);

/// An emissive shape's "emission": an absolute spectral radiance, or {"spectrum": ..., one amount (lm, W, nt,
/// W/m2/sr, EV)} with lumens spread over the mesh's world-space area (both faces if two-sided).
LightSpectrum area_light_emission(const JsonCursor& emission, const TriangleMesh& mesh, bool two_sided,
                                  LoadContext& context);
/// The same for an emitting surface of world-space area `area_m2` per side (an analytic sphere's 4πr²).
LightSpectrum area_light_emission(const JsonCursor& emission, double area_m2, bool two_sided, LoadContext& context);

/// An emissive medium's "emission" radiance L_e (MediumEmission): an absolute spectral radiance, or {"spectrum": ...,
/// "luminance_nt" | "radiance_w_m2_sr" | "ev100"}, the luminance an optically thick body of the medium shows.
LightSpectrum medium_emission_radiance(const JsonCursor& emission, LoadContext& context);

/// True if an emissive shape's "emission" is an image: an object with an "image" key.
bool is_emission_image(const JsonCursor& emission);
/// An emissive mesh's image emission: {"image": file, optional "colour_space", "encoding", and "scale" (film units,
/// like an environment image's) or "white_luminance_nt" (the luminance of a pixel of luminance 1, a display's white).
/// Errors name the key.
EmissionImage area_emission_image(const JsonCursor& emission, LoadContext& context);

/// A light with "include": "file.json" (a definition written by rimu-light): the file's object with the scene
/// light's other keys laid over it (position, direction... or any override). Errors name both files.
nlohmann::json included_light(const JsonCursor& light, const std::filesystem::path& scene_directory);

/// World-space area of triangles (three indices each), m²: what an area light's lumens are spread over.
double mesh_area_m2(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices);

}  // namespace rimu::scene_loading
