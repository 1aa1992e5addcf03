#include "transport/lights/light_sampler.h"

#include "transport/lights/bvh_light_sampler.h"
#include "transport/lights/power_light_sampler.h"

namespace rimu {

std::optional<LightSamplerKind> parse_light_sampler_kind(std::string_view name) {
  if (name == "bvh") return LightSamplerKind::bvh;
  if (name == "bvh-spectral") return LightSamplerKind::bvh_spectral;
  if (name == "power") return LightSamplerKind::power;
  if (name == "uniform") return LightSamplerKind::uniform;
  return std::nullopt;
}

const char* light_sampler_kind_name(LightSamplerKind kind) {
  switch (kind) {
    case LightSamplerKind::bvh:
      return "bvh";
    case LightSamplerKind::bvh_spectral:
      return "bvh-spectral";
    case LightSamplerKind::power:
      return "power";
    case LightSamplerKind::uniform:
      return "uniform";
  }
  return "bvh";
}

std::unique_ptr<LightSampler> make_light_sampler(LightSamplerKind kind, std::span<const Light* const> lights,
                                                 double scene_radius_m) {
  switch (kind) {
    case LightSamplerKind::power:
      return std::make_unique<PowerLightSampler>(lights, scene_radius_m);
    case LightSamplerKind::uniform:
      return std::make_unique<PowerLightSampler>(PowerLightSampler::uniform_over_lights(lights, scene_radius_m));
    case LightSamplerKind::bvh_spectral:
      return std::make_unique<BvhLightSampler>(lights, BvhLightSampler::Importance::spectral);
    case LightSamplerKind::bvh:
      break;
  }
  return std::make_unique<BvhLightSampler>(lights);
}

}  // namespace rimu
