#include "render/scene/light_coverage.h"

#include <cmath>
#include <cstdio>

#include "transport/lights/light.h"

namespace rimu {
namespace {

constexpr int kMaxCheckedLights = 2000;
constexpr int kExactPartLimit = 64;
constexpr int kChoiceDraws = 4096;
constexpr int kOwnSamples = 16;
constexpr int kOtherSamples = 256;

const SampledWavelengths& probe_wavelengths() {
  static const SampledWavelengths lambda(Float4(450.0f, 500.0f, 550.0f, 600.0f), Float4(1.0f));
  return lambda;
}

float lane_mean(const SampledSpectrum& s) { return sum(s) / float(kLaneCount); }

// The irradiance one light sample carries at (p, n), divided by its density.
double irradiance_term(const LightSample& s, Vec3 normal) {
  const float cos_theta = dot(s.wi, normal);
  if (!(cos_theta > 0.0f) || !(s.pdf_solid_angle > 0.0f)) return 0.0;
  return double(lane_mean(s.radiance)) * cos_theta / s.pdf_solid_angle;
}

// Van der Corput radical inverse in base 2 (stratified second coordinates).
float radical_inverse(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
  i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
  i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
  i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
  return float(i) * 0x1p-32f;
}

struct Probe {
  Vec3 position, normal;
};

// The nearest surface hit along the light's axis, or along the six axis directions when it has none.
std::optional<Probe> probe_for(const Scene& scene, const Light& light) {
  LightBounds all;
  Vec3 axis_sum{};
  for (int k = 0; k < light.part_count(); ++k)
    if (const auto b = light.part_bounds(k)) {
      all = unite(all, *b);
      if (b->cos_theta_o > -0.99f) axis_sum += b->axis * b->intensity_w_sr;
    }
  if (!(all.intensity_w_sr > 0.0f)) return std::nullopt;
  std::vector<Vec3> directions;
  if (length(axis_sum) > 1e-3f * all.intensity_w_sr) {
    directions.push_back(normalize(axis_sum));
  } else {
    directions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  }
  std::optional<Probe> best;
  float best_t = INFINITY;
  for (Vec3 d : directions) {
    Ray ray;
    ray.origin = all.centre_m();
    ray.direction = d;
    ray.t_min = 1e-4f * scene.scene_scale;
    ray.t_max = INFINITY;
    const auto hit = scene.geometry.intersect(ray);
    if (!hit || hit->light >= 0 || !(hit->t < best_t)) continue;
    best_t = hit->t;
    best = Probe{hit->position, face_forward(hit->geometric_normal, -d)};
  }
  return best;
}

}  // namespace

std::vector<LightCoverage> light_coverage(const Scene& scene) {
  std::vector<LightCoverage> out;
  const LightSampler& sampler = *scene.light_sampler;
  const SampledWavelengths& lambda = probe_wavelengths();
  int checked = 0;
  for (size_t l = 0; l < scene.lights.size() && checked < kMaxCheckedLights; ++l) {
    const Light& light = *scene.lights[l];
    if (light.is_infinite()) continue;
    ++checked;
    const std::optional<Probe> probe = probe_for(scene, light);
    if (!probe) continue;
    // Just off the surface, on the lit side, as the integrators shade it.
    const Vec3 position = probe->position + probe->normal * (1e-5f * scene.scene_scale);
    const LightSamplingPoint at{position, probe->normal};
    const LightReference ref{position, probe->normal};

    double own = 0.0;
    for (int i = 0; i < kOwnSamples; ++i)
      if (const auto s = light.sample_li(ref, lambda, {(float(i) + 0.5f) / kOwnSamples, radical_inverse(uint32_t(i))}))
        own += irradiance_term(*s, probe->normal) / kOwnSamples;
    if (!(own > 0.0)) continue;

    double others = 0.0;
    for (int i = 0; i < kOtherSamples; ++i) {
      const auto choice = sampler.sample(at, (float(i) + 0.5f) / kOtherSamples);
      if (!choice || size_t(choice->light) == l) continue;
      const Light& other = *scene.lights[size_t(choice->light)];
      const Vec2 u{radical_inverse(uint32_t(i)), radical_inverse(uint32_t(i) * 2654435761u)};
      if (const auto s = other.sample_part_li(choice->part, ref, lambda, u))
        others += irradiance_term(*s, probe->normal) / (double(choice->probability) * kOtherSamples);
    }

    double share = 0.0;
    if (!sampler.chooses_parts()) {
      share = sampler.pmf(at, int(l), -1);
    } else if (light.part_count() <= kExactPartLimit) {
      for (int k = 0; k < light.part_count(); ++k) share += sampler.pmf(at, int(l), k);
    } else {
      int hits = 0;
      for (int i = 0; i < kChoiceDraws; ++i) {
        const auto choice = sampler.sample(at, (float(i) + 0.5f) / kChoiceDraws);
        if (choice && size_t(choice->light) == l) ++hits;
      }
      share = double(hits) / kChoiceDraws;
    }
    out.push_back({int(l), position, share, own / (own + others)});
  }
  return out;
}

std::vector<std::string> light_coverage_warnings(const Scene& scene) {
  std::vector<std::string> warnings;
  for (const LightCoverage& c : light_coverage(scene)) {
    if (!c.starved()) continue;
    const std::string name =
        size_t(c.light) < scene.light_names.size() ? scene.light_names[size_t(c.light)] : "light " + std::to_string(c.light);
    char text[320];
    std::snprintf(text, sizeof text,
                  "%s gets %.2g %% of the light samples at (%.3g, %.3g, %.3g) m, the surface it lights, where it "
                  "gives %.0f %% of the unshadowed direct light: expect noise there",
                  name.c_str(), 100.0 * c.sample_share, c.probe_m.x, c.probe_m.y, c.probe_m.z,
                  100.0 * c.irradiance_share);
    std::string message = text;
    if (scene.settings.light_sampler != LightSamplerKind::bvh &&
        scene.settings.light_sampler != LightSamplerKind::bvh_spectral)
      message += std::string(" (\"light_sampler\": \"") + light_sampler_kind_name(scene.settings.light_sampler) +
                 "\"; \"bvh\" chooses lights by their contribution at each point)";
    warnings.push_back(message);
  }
  return warnings;
}

}  // namespace rimu
