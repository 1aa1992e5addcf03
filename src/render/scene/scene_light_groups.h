// A light's "light_group" key: which layer of the EXR its emission goes to (light groups, docs/scene-format.md).
#pragma once

#include <string>

#include "render/scene/json_cursor.h"
#include "render/scene/scene.h"

namespace rimu::scene_loading {

/// The group every light without a "light_group" key joins in a scene that names groups, so the layers always sum
/// to the beauty. A light may also name it.
inline constexpr const char* kDefaultLightGroup = "ungrouped";

/// Checks a group name: 1 to 64 characters of A-Z, a-z, 0-9, '_' and '-', and not a name Rimu gives its own EXR
/// channels or layers (X, Y, Z, R, G, B, A, S0, rimu, spp, relativeError and the feature buffers' layers, in any case),
/// so that `<group>.X` can never be taken for another channel. Returns the reason it is refused, or "" if valid.
std::string light_group_name_problem(const std::string& name);

/// Reads `light`'s "light_group" (if it has one) and records it on the light just loaded into `scene.lights`:
/// its group index in `scene.light_groups` (names in order of first use). A light without the key is marked
/// ungrouped until finish_light_groups(). InputError naming the key for a bad name.
void read_light_group(const JsonCursor& light, Scene& scene);

/// The group of an emissive medium's "light_group" (as read_light_group), or −1 (ungrouped until
/// finish_light_groups()) without the key. The caller records it with Medium::set_emission.
int read_medium_light_group(const JsonCursor& medium, Scene& scene);

/// After every light and medium is loaded: with no "light_group" key anywhere, every light is in group 0 and the scene has no
/// groups (no layers, no per-sample cost); otherwise the unmarked lights join kDefaultLightGroup (added last if no
/// light named it).
void finish_light_groups(Scene& scene);

}  // namespace rimu::scene_loading
