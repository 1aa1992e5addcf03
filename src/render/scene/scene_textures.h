// Internal to scene loading: float and spectral texture values of the JSON format (docs/scene-format.md, "Textures").
#pragma once

#include "render/scene/scene_load_context.h"
#include "transport/textures/float_texture.h"
#include "transport/textures/spectral_texture.h"

namespace rimu::scene_loading {

/// A number in [min, max], or a float texture object ({"texture": ...}, {"product": [a, b]}, {"mix": [a, b],
/// "amount": t}, {"direction_mix": [a, b], "direction": v}, {"checkerboard": [a, b], "uv_scale", "uv_offset"} or
/// another "mapping", {"dots": [inside, outside], ...}, {"noise": "fbm" | "wrinkled" | "windy", ...}),
/// whose inputs are float values in turn. Only top-level numbers are range-checked; textures are clamped where used.
FloatTexturePtr load_float_texture(const JsonCursor& value, LoadContext& context, double min, double max);
/// A reflectance: a spectral input, an image {"texture": "file.png", ...}, or the combinators above with spectral
/// inputs ("product": [spectral, float]; "amount" is a float value), or {"noise": "marble", ...}.
SpectralTexturePtr load_spectral_texture(const JsonCursor& value, LoadContext& context);

}  // namespace rimu::scene_loading
