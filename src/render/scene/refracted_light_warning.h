// A load-time check for lights that next-event estimation cannot reach because refracting glass is in the way.
//
// Shadow rays pass panes (thin dielectrics) and cut-outs, but stop at refracting surfaces (a dielectric, smooth or
// rough: its transmission bends rays, so no straight shadow ray follows the light's path; docs/transport.md,
// "Glazing"). Light behind such glass arrives by BSDF sampling alone: noisy, and from a small distant light (the
// sun) practically never. The heuristic: for each light at infinity (a sun, a sky), probe points are the camera's
// position and the first surfaces seen from it along the 26 directions of a 3×3×3 lattice (nudged back towards the
// camera); from each, 4 light samples are traced to the light, passing panes, cut-outs and (for this check only)
// refracting surfaces, and stopping at anything opaque. The light is reported when at least 90 % of the samples that
// reach it pass a refracting surface (not all: a probe on the wall beside a window can see the sky past a pane's
// edge): from where the camera looks, it is seen through refracting glass (e.g. a sky behind a window modelled as
// a `dielectric`). A sun whose rays reach none of the probe points (a patch near the window, the camera far from
// it) is not judged. Finite lights are not checked (a lamp in
// a glass bulb is a deliberate choice, and its bulb is usually not the only way out).
//
// A second check, for media: a scattering medium bounded by a smooth refracting dielectric (a subsurface walk
// written without `diffuse_entry`) never receives light from point, spot, goniometric or distant lights (shadow rays
// from inside stop at its surface, and no path that leaves it can hit a delta light or practically a sun). It is
// reported when the scene has such a light.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/scene/scene.h"

namespace rimu {

/// One message per light at infinity reached from the probe points only through refracting surfaces (above).
std::vector<std::string> refracted_light_warnings(const Scene& scene);

/// One message per medium (the scene's JSON `document`, as loaded into `scene`) that scatters beneath a smooth
/// `dielectric` without `diffuse_entry`, when `scene` has a delta or directional light (above).
std::vector<std::string> unlit_medium_warnings(const nlohmann::json& document, const Scene& scene);

}  // namespace rimu
