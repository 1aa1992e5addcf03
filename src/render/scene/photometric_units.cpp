#include "render/scene/photometric_units.h"

namespace rimu {

bool uses_photometric_units(const nlohmann::json& value) {
  if (value.is_object()) {
    for (const char* key : {"luminous_power_lm", "luminous_intensity_cd", "illuminance_lx", "luminance_nt"})
      if (value.contains(key)) return true;
    if (const auto type = value.find("type"); type != value.end() && (*type == "ies" || *type == "goniometric")) return true;
  }
  if (value.is_object() || value.is_array())
    for (const auto& item : value)
      if (uses_photometric_units(item)) return true;
  return false;
}

}  // namespace rimu
