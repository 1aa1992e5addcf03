#include "render/scene/scene_portals.h"

#include <vector>

namespace rimu::scene_loading {

PortalSet load_portals(const JsonCursor& l) {
  if (!l.has("portals")) return {};
  const JsonCursor list = l.at("portals");
  if (!list.is_array() || list.size() == 0) list.fail("expected a non-empty array of portals, each [c0, c1, c2, c3]");
  std::vector<PortalRectangle> portals;
  for (size_t i = 0; i < list.size(); ++i) {
    const JsonCursor p = list.at(i);
    if (!p.is_array() || p.size() != 4) p.fail("expected the four corners of a rectangle, in order: [c0, c1, c2, c3]");
    const auto rectangle = PortalRectangle::from_corners(p.at(0).vec3(), p.at(1).vec3(), p.at(2).vec3(), p.at(3).vec3());
    if (!rectangle)
      p.fail("the four corners must form a rectangle in order (c2 = c1 + c3 - c0 and a right angle at c0, to 1e-3 of "
             "the longer edge), with no edge of zero length");
    portals.push_back(*rectangle);
  }
  return PortalSet(std::move(portals));
}

}  // namespace rimu::scene_loading
