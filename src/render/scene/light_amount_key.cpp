#include "render/scene/light_amount_key.h"

#include <string>

namespace rimu {

std::optional<KeyedLightAmount> read_light_amount(const JsonCursor& object) {
  const LightAmountKey* given = nullptr;
  for (const LightAmountKey& k : kLightAmountKeys) {
    if (!object.has(k.key)) continue;
    if (given) object.at(k.key).fail(std::string("a light takes one amount; '") + given->key + "' is given too");
    given = &k;
  }
  if (!given) return std::nullopt;
  const JsonCursor value = object.at(given->key);
  return KeyedLightAmount{given, {given->unit == LightUnit::ev100 ? value.number(kMinEv100, kMaxEv100)
                                                                  : value.number(kMinLightAmount, kMaxLightAmount),
                                  given->unit}};
}

}  // namespace rimu
