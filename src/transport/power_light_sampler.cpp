#include "transport/power_light_sampler.h"

#include <vector>

#include "transport/light.h"

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

PowerLightSampler::PowerLightSampler(std::span<const Light* const> lights, std::span<const double> weights)
    : distribution_(weights) {
  parts_.resize(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    const int count = lights[i]->part_count();
    if (count <= 1) continue;
    std::vector<double> part_power(static_cast<size_t>(count));
    for (int k = 0; k < count; ++k) part_power[size_t(k)] = lights[i]->part_power_w(k);
    parts_[i] = Distribution1D(part_power);
  }
}

PowerLightSampler::PowerLightSampler(std::span<const Light* const> lights, double scene_radius_m)
    : PowerLightSampler(lights, powers_of(lights, scene_radius_m)) {}

PowerLightSampler PowerLightSampler::uniform_over_lights(std::span<const Light* const> lights,
                                                         double scene_radius_m) {
  return PowerLightSampler(lights, unit_weights(lights, scene_radius_m));
}

std::optional<PowerLightSampler::Pick> PowerLightSampler::pick(float u) const {
  if (distribution_.is_zero()) return std::nullopt;
  const auto s = distribution_.sample_discrete(u);
  return Pick{s.index, s.probability};
}

std::optional<LightChoice> PowerLightSampler::sample(const LightSamplingPoint&, float u) const {
  if (distribution_.is_zero()) return std::nullopt;
  const auto s = distribution_.sample_discrete(u);
  if (size_t(s.index) >= parts_.size() || parts_[size_t(s.index)].size() == 0)
    return LightChoice{s.index, 0, s.probability};
  const Distribution1D& parts = parts_[size_t(s.index)];
  if (parts.is_zero()) return std::nullopt;  // a light with power but no part carrying it: never happens
  const auto part = parts.sample_discrete(s.u_remapped);
  return LightChoice{s.index, part.index, s.probability * part.probability};
}

float PowerLightSampler::pmf(const LightSamplingPoint&, int light, int part) const {
  const float p = distribution_.probability(light);
  if (!(p > 0.0f)) return 0.0f;
  if (size_t(light) >= parts_.size() || parts_[size_t(light)].size() == 0) return part == 0 ? p : 0.0f;
  return p * parts_[size_t(light)].probability(part);
}

}  // namespace rimu
