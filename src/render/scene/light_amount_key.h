// The keys a light's amount is written under, in a scene's light and in a light definition (rimu-light's files):
// one key per unit, e.g. "luminous_power_lm": 800 (docs/light-units.md).
#pragma once

#include <array>
#include <optional>

#include "render/scene/json_cursor.h"
#include "spectral/photometry/light_units.h"

namespace rimu {

struct LightAmountKey {
  const char* key;
  LightUnit unit;
};

/// Every amount key, in the order light definitions are written.
inline constexpr std::array kLightAmountKeys{
    LightAmountKey{"luminous_power_lm", LightUnit::lumen},       LightAmountKey{"radiant_power_w", LightUnit::watt},
    LightAmountKey{"luminous_intensity_cd", LightUnit::candela}, LightAmountKey{"radiant_intensity_w_sr", LightUnit::watt_per_sr},
    LightAmountKey{"illuminance_lx", LightUnit::lux},            LightAmountKey{"irradiance_w_m2", LightUnit::watt_per_m2},
    LightAmountKey{"luminance_nt", LightUnit::nit},              LightAmountKey{"radiance_w_m2_sr", LightUnit::watt_per_m2_sr},
    LightAmountKey{"ev100", LightUnit::ev100},
};

/// An amount and the key it was given under.
struct KeyedLightAmount {
  const LightAmountKey* key;
  LightAmount amount;
};

/// The one amount key of the object `object`, its value in the range of light amounts (light_units.h); nullopt if
/// it has none. Errors (at the key): a second amount key, a value out of range.
std::optional<KeyedLightAmount> read_light_amount(const JsonCursor& object);

}  // namespace rimu
