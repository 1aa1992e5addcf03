#include "transport/lights/light_sampler.h"

#include "transport/lights/bvh_light_sampler.h"
#include "transport/lights/power_light_sampler.h"

#include <vector>

#include "transport/lights/light.h"

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
  // By power (or 1 per light with power), 0 for lights left to BSDF sampling (Light::sampled_by_nee).
  const auto weights = [&](bool uniform) {
    std::vector<double> w;
    for (const Light* light : lights) {
      const double power = light->sampled_by_nee() ? light->total_power_w(scene_radius_m) : 0.0;
      w.push_back(uniform ? (power > 0.0 ? 1.0 : 0.0) : power);
    }
    return w;
  };
  switch (kind) {
    case LightSamplerKind::power:
      return std::make_unique<PowerLightSampler>(weights(false));
    case LightSamplerKind::uniform:
      return std::make_unique<PowerLightSampler>(weights(true));
    case LightSamplerKind::bvh_spectral:
      return std::make_unique<BvhLightSampler>(lights, BvhLightSampler::Importance::spectral);
    case LightSamplerKind::bvh:
      break;
  }
  return std::make_unique<BvhLightSampler>(lights);
}

}  // namespace rimu
