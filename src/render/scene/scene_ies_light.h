// A scene light of type "ies": a goniometric point light from an IES LM-63 file (render/scene/ies_file.h). Internal to
// scene loading.
//
//   {"type": "ies", "file": "downlight.ies", "position": [0, 3, 0], "direction": [0, -1, 0],
//    "c0_direction": [1, 0, 0], "spectrum": {"blackbody": 3000}, "luminous_power_lm": 1200 | "candela_scale": 2}
//
// "direction" is the photometric axis (γ = 0, nadir for a downlight; default straight down), "c0_direction" the
// C = 0° plane (default: world +x, or +z if the axis is along x). The file's candela values are taken as they
// are (absolute; for relative photometry they are the values for the rated lamp lumens), times "candela_scale";
// or the table is scaled so that the light emits "luminous_power_lm" in all (∫I dω; this is the luminaire's
// output, the file's lamp lumens times its efficiency). "spectrum" is the shape, normalised so that one table unit
// is one candela: I(λ, ω) = table(ω) · S(λ) / (K_m Σ S V Δλ).
#pragma once

#include <memory>

#include "render/scene/scene_load_context.h"
#include "transport/geometry/frame.h"
#include "transport/lights/light.h"

namespace rimu::scene_loading {

/// Loads an "ies" light; errors name the key, or the IES file and line.
std::unique_ptr<Light> load_ies_light(const JsonCursor& light, LoadContext& context);

/// Loads a "goniometric" light: pbrt-v4's goniometric light, an equal-area octahedral image of intensities
/// (transport/lights/equal_area_intensity.h) whose local x, y, z are `frame`'s s, t, n.
///
///   {"type": "goniometric", "image": "lamp.exr", "position": [0, 3, 0], "frame": [s, t, n],
///    "spectrum": {"blackbody": 3000}, "candela_scale": 2 | "luminous_power_lm": 1200}
///
/// A pixel's value is the mean of its R, G, B (pbrt's), in candela times "candela_scale", or scaled so that the
/// light emits "luminous_power_lm"; the spectrum is normalised as an "ies" light's.
std::unique_ptr<Light> load_goniometric_image_light(const JsonCursor& light, LoadContext& context, const Frame& frame);

}  // namespace rimu::scene_loading
