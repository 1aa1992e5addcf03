// The "lights" section of the JSON scene format (radiometric units; see docs/scene-format.md).
#include <cmath>

#include "render/scene_load_context.h"
#include "transport/distant_light.h"
#include "transport/environment_light.h"
#include "transport/light_spectrum.h"
#include "transport/point_light.h"
#include "transport/spot_light.h"

namespace rimu::scene_loading {
namespace {

LightSpectrum spectrum_of(const JsonCursor& light, const char* key, LoadContext& context) {
  return LightSpectrum(context.spectra.parse(light.at(key), SpectrumRole::emission), 1.0);
}

Vec3 unit_direction(const JsonCursor& c) {
  const Vec3 d = c.vec3();
  if (!(length(d) > 0.0f)) c.fail("a direction cannot be zero");
  return normalize(d);
}

std::unique_ptr<Light> load_light(const JsonCursor& l, LoadContext& context) {
  const std::string type = l.at("type").choice({"point", "spot", "distant", "environment"});
  if (type == "point") {
    l.only_keys({"type", "name", "position", "intensity"});
    return std::make_unique<PointLight>(l.at("position").vec3(), spectrum_of(l, "intensity", context));
  }
  if (type == "spot") {
    l.only_keys({"type", "name", "position", "direction", "cone_angle_deg", "falloff_start_deg", "intensity"});
    const double outer = l.at("cone_angle_deg").number(0.01, 179.9) / 2.0;
    const double inner = l.has("falloff_start_deg") ? l.at("falloff_start_deg").number(0.0, 2.0 * outer) / 2.0 : outer;
    return std::make_unique<SpotLight>(l.at("position").vec3(), unit_direction(l.at("direction")), inner, outer,
                                       spectrum_of(l, "intensity", context));
  }
  if (type == "distant") {
    l.only_keys({"type", "name", "direction", "irradiance", "angular_diameter_deg"});
    return std::make_unique<DistantLight>(unit_direction(l.at("direction")), spectrum_of(l, "irradiance", context),
                                          l.number_or("angular_diameter_deg", 0.0, 0.0, 90.0));
  }
  l.only_keys({"type", "name", "radiance"});
  return std::make_unique<EnvironmentLight>(spectrum_of(l, "radiance", context));
}

}  // namespace

void load_lights(const JsonCursor& section, LoadContext& context) {
  for (size_t i = 0; i < section.size(); ++i) context.scene.lights.push_back(load_light(section.at(i), context));
}

}  // namespace rimu::scene_loading
