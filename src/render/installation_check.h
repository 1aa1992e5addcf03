// What Rimu loads only when a scene needs it, loaded up front: `rimu --check-install` (docs/farm.md, "Checking a
// node"). A render finds a missing module only at its first use (a farm node without FreeImage fails at the
// first PFM sky); this finds it before any task runs.
#pragma once

#include <string>
#include <vector>

namespace rimu {

struct InstallationItem {
  std::string name;    ///< "data folder", "OpenImageIO module", …
  bool ok = false;
  std::string detail;  ///< where it was found, or why it failed (the error a render would give)
};

/// Finds the data folder, loads the OpenImageIO, FreeImage and OpenColorIO modules and builds the default display
/// transform from the shipped OpenColorIO config; one item per part, in that order. Never throws for a missing part.
std::vector<InstallationItem> check_installation();

}  // namespace rimu
