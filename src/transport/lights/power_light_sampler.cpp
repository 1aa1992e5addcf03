#include "transport/lights/power_light_sampler.h"

#include <vector>

#include "transport/lights/light.h"

namespace rimu {
namespace {

std::vector<double> powers_of(std::span<const Light* const> lights, double scene_radius_m) {
  std::vector<double> power_w;
  power_w.reserve(lights.size());
  for (const Light* light : lights) power_w.push_back(light->total_power_w(scene_radius_m));
  return power_w;
}

std::vector<double> unit_weights(std::span<const Light* const> lights, double scene_radius_m) {
  std::vector<double> weights;
  for (const Light* light : lights) weights.push_back(light->total_power_w(scene_radius_m) > 0.0 ? 1.0 : 0.0);
  return weights;
}

}  // namespace

PowerLightSampler::PowerLightSampler(std::span<const double> power_w) : distribution_(power_w) {}

PowerLightSampler::PowerLightSampler(std::span<const Light* const> lights, double scene_radius_m)
    : distribution_(powers_of(lights, scene_radius_m)) {}

PowerLightSampler PowerLightSampler::uniform_over_lights(std::span<const Light* const> lights,
                                                         double scene_radius_m) {
  return PowerLightSampler(unit_weights(lights, scene_radius_m));
}

std::optional<PowerLightSampler::Pick> PowerLightSampler::pick(float u) const {
  if (distribution_.is_zero()) return std::nullopt;
  const auto s = distribution_.sample_discrete(u);
  return Pick{s.index, s.probability};
}

std::optional<LightChoice> PowerLightSampler::sample(const LightSamplingPoint&, float u) const {
  if (distribution_.is_zero()) return std::nullopt;
  const auto s = distribution_.sample_discrete(u);
  return LightChoice{s.index, -1, s.probability};
}

float PowerLightSampler::pmf(const LightSamplingPoint&, int light, int part) const {
  return part == -1 ? distribution_.probability(light) : 0.0f;
}

}  // namespace rimu
