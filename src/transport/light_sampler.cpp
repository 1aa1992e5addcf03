#include "transport/light_sampler.h"

#include <vector>

#include "transport/light.h"

namespace rimu {

LightSampler::LightSampler(std::span<const double> power_w) : distribution_(power_w) {}

namespace {
std::vector<double> powers_of(std::span<const Light* const> lights, double scene_radius_m) {
  std::vector<double> power_w;
  power_w.reserve(lights.size());
  for (const Light* light : lights) power_w.push_back(light->total_power_w(scene_radius_m));
  return power_w;
}
}  // namespace

LightSampler::LightSampler(std::span<const Light* const> lights, double scene_radius_m)
    : distribution_(powers_of(lights, scene_radius_m)) {}

std::optional<LightSampler::Pick> LightSampler::pick(float u) const {
  if (distribution_.is_zero()) return std::nullopt;
  const auto s = distribution_.sample_discrete(u);
  return Pick{s.index, s.probability};
}

}  // namespace rimu
