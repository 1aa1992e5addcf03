// Whether a scene's lights are given in photometric units: such scenes are in the tens to thousands of nits, which
// film units (Y = 1 ↔ 72 983 nt) show at a few codes of 255, so `rimu` meters their display image
// (render/output/display_image_policy.h).
#pragma once

#include <nlohmann/json.hpp>

namespace rimu {

/// True if any object in `value` (a scene document, a light, a light definition) gives an amount in photometric
/// units (luminous_power_lm, luminous_intensity_cd, illuminance_lx, luminance_nt) or is an "ies" or "goniometric"
/// light (tabulated in candela).
bool uses_photometric_units(const nlohmann::json& value);

}  // namespace rimu
