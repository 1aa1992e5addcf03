// "portals" of a light at infinity (an "environment" or a "cie_sky"): the windows and skylights through which it
// reaches the scene (transport/lights/environment_portal.h). Internal to scene loading; docs/scene-format.md describes
// the key.
#pragma once

#include "render/scene/json_cursor.h"
#include "transport/lights/environment_portal.h"

namespace rimu::scene_loading {

/// "portals": [[c0, c1, c2, c3], ...], each the four corners of a rectangle in order; an empty set without the key.
/// Errors name the portal's key.
PortalSet load_portals(const JsonCursor& light);

}  // namespace rimu::scene_loading
