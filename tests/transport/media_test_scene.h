// Test scenes for participating media: an infinite slab between two analytic planes, a uniform sky, and helpers
// that average many camera samples per lane.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "spectral/spectra/spectrum.h"
#include "transport/lights/distant_light.h"
#include "transport/lights/light_warps.h"
#include "transport/lights/power_light_sampler.h"
#include "transport/integrators/volumetric_path_integrator.h"
#include "transport/sampling/sampler.h"

namespace rimu::test {

/// A spectrum that is constant over each of four wavelength bands, so that the lanes at 400, 500, 600, 700 nm
/// (kTestLambda) see exactly the four given values.
class BandSpectrum final : public Spectrum {
 public:
  BandSpectrum(float a, float b, float c, float d) : v_{a, b, c, d} {}
  double value(double nm) const override { return v_[nm < 450 ? 0 : nm < 550 ? 1 : nm < 650 ? 2 : 3]; }
  double max_value() const override { return std::max(std::max(v_[0], v_[1]), std::max(v_[2], v_[3])); }
  std::string describe() const override { return "band spectrum"; }

 private:
  float v_[4];
};

inline SpectrumPtr bands(float a, float b, float c, float d) { return std::make_shared<BandSpectrum>(a, b, c, d); }
inline SpectrumPtr bands(Float4 v) { return bands(v[0], v[1], v[2], v[3]); }

/// The four test wavelengths, one per band.
inline SampledWavelengths test_lambda() { return {Float4(400.0f, 500.0f, 600.0f, 700.0f), Float4(1.0f / 470.0f)}; }

/// The slab z ∈ [0, thickness] (infinite in x, y) bounded by two planes of material 0 (outward normals −z and +z),
/// so rays entering it from either side enter the medium that material 0 encloses.
class SlabGeometry final : public RayQueries {
 public:
  explicit SlabGeometry(float thickness_m) : thickness_(thickness_m) {}
  std::optional<SurfaceHit> intersect(const Ray& ray) const override {
    std::optional<SurfaceHit> best;
    for (int side = 0; side < 2; ++side) {
      if (ray.direction.z == 0.0f) break;
      const float z = side == 0 ? 0.0f : thickness_;
      const float t = (z - ray.origin.z) / ray.direction.z;
      if (!(t > ray.t_min) || !(t < ray.t_max) || (best && t >= best->t)) continue;
      SurfaceHit hit;
      hit.t = t;
      hit.position = ray.origin + ray.direction * t;
      hit.position.z = z;
      hit.geometric_normal = hit.shading_normal = Vec3{0.0f, 0.0f, side == 0 ? -1.0f : 1.0f};
      hit.material = 0;
      best = hit;
    }
    return best;
  }
  bool occluded(const Ray& ray) const override { return intersect(ray).has_value(); }

 private:
  float thickness_;
};

/// Radiance L from every direction at infinity (a white furnace when L = 1).
class UniformSky final : public Light {
 public:
  explicit UniformSky(float radiance) : radiance_(radiance) {}
  std::optional<LightSample> sample_li(const LightReference&, const SampledWavelengths&, Vec2 u) const override {
    LightSample s;
    s.wi = sample_uniform_sphere(u);
    s.radiance = Float4(radiance_);
    s.pdf_solid_angle = float(0.25 * std::numbers::inv_pi);
    return s;
  }
  float pdf_li(const LightReference&, Vec3, const SurfaceHit*) const override { return float(0.25 * std::numbers::inv_pi); }
  SampledSpectrum radiance_escaped(Vec3, const SampledWavelengths&) const override { return Float4(radiance_); }
  double total_power_w(double) const override { return 1.0; }
  bool is_infinite() const override { return true; }

 private:
  float radiance_;
};

/// A slab of one medium with either index-matched boundaries (`boundary_ior` = 0) or a smooth dielectric, which
/// lets light in diffusely with `diffuse_entry` (DielectricBsdf, "Diffuse entry").
struct SlabScene {
  SlabGeometry geometry;
  std::vector<Material> materials;
  std::vector<std::unique_ptr<Light>> lights;
  std::unique_ptr<LightSampler> light_sampler;
  std::vector<Medium> media;
  std::vector<MediumBoundary> boundaries;
  TransportScene surfaces;
  VolumetricScene scene;

  SlabScene(float thickness_m, Medium medium, std::unique_ptr<Light> light, float boundary_ior = 0.0f,
            bool diffuse_entry = false)
      : geometry(thickness_m) {
    const float ior = boundary_ior > 0.0f ? boundary_ior : 1.0f;
    DielectricMaterial boundary(std::make_shared<ConstantSpectrum>(ior), 0.0f);
    if (diffuse_entry) boundary.use_diffuse_entry();
    materials.push_back(std::move(boundary));
    media.push_back(std::move(medium));
    boundaries.push_back({0, boundary_ior == 0.0f});
    const bool infinite = light->is_infinite();
    lights.push_back(std::move(light));
    const double power[] = {1.0};
    light_sampler = std::make_unique<PowerLightSampler>(power);
    surfaces.geometry = &geometry;
    surfaces.materials = &materials;
    surfaces.lights = &lights;
    surfaces.light_sampler = light_sampler.get();
    if (infinite) surfaces.infinite_lights = {0};
    surfaces.scene_scale = std::fmax(thickness_m, 1e-3f);
    scene = {surfaces, &media, &boundaries};
  }
  SlabScene(const SlabScene&) = delete;
};

/// Per-lane mean and standard error of a set of samples, and what went wrong.
struct LaneStatistics {
  double mean[4] = {}, standard_error[4] = {}, max_value[4] = {};
  int non_finite = 0;
};

/// Averages `count` estimates produced by estimate(i) (returns a Float4) per lane.
template <typename F>
LaneStatistics lane_statistics(int count, F&& estimate) {
  LaneStatistics s;
  double sum[4] = {}, sum2[4] = {};
  for (int i = 0; i < count; ++i) {
    const Float4 v = estimate(i);
    for (int k = 0; k < 4; ++k) {
      if (!std::isfinite(v[k])) {
        ++s.non_finite;
        continue;
      }
      sum[k] += v[k];
      sum2[k] += double(v[k]) * v[k];
      s.max_value[k] = std::max(s.max_value[k], double(v[k]));
    }
  }
  for (int k = 0; k < 4; ++k) {
    s.mean[k] = sum[k] / count;
    const double variance = std::max(0.0, sum2[k] / count - s.mean[k] * s.mean[k]);
    s.standard_error[k] = std::sqrt(variance / count);
  }
  return s;
}

/// The radiance estimate of sample `i` at the four test wavelengths, with the hero rotated through the lanes
/// (sample i makes lane i mod 4 the hero): spectral MIS is unbiased per lane only over the hero's rotation, which
/// the renderer gets from its random hero and the tests from this rotation.
inline Float4 rotated_radiance(const VolumetricPathIntegrator& integrator, const Ray& ray, Sampler& sampler, int i) {
  const auto base = test_lambda().lambda_nm().to_array();
  const int r = i % 4;
  const SampledWavelengths lambda(Float4(base[size_t(r)], base[size_t((r + 1) % 4)], base[size_t((r + 2) % 4)],
                                         base[size_t((r + 3) % 4)]),
                                  Float4(1.0f / 470.0f));
  const auto out = integrator.radiance(ray, lambda, sampler).to_array();
  std::array<float, 4> lanes{};
  for (int l = 0; l < 4; ++l) lanes[size_t((r + l) % 4)] = out[size_t(l)];
  return Float4(lanes[0], lanes[1], lanes[2], lanes[3]);
}

/// `count` estimates of the radiance along `ray` by the volumetric integrator with `settings`, the hero rotated
/// through the lanes (rotated_radiance), from an independent sampler seeded with `seed`.
inline LaneStatistics render_ray(const VolumetricScene& scene, const VolumetricIntegratorSettings& settings,
                                 const Ray& ray, int count, uint64_t seed = 7) {
  const VolumetricPathIntegrator integrator(scene, settings);
  IndependentSampler sampler(seed);
  return lane_statistics(count, [&](int i) {
    sampler.start_pixel_sample(i, 0, 0);
    return rotated_radiance(integrator, ray, sampler, i);
  });
}
inline LaneStatistics render_ray(const SlabScene& slab, const VolumetricIntegratorSettings& settings, const Ray& ray,
                                 int count, uint64_t seed = 7) {
  return render_ray(slab.scene, settings, ray, count, seed);
}

/// A unit direction with cosine-weighted density around `axis` (±z), from u.
inline Vec3 cosine_direction(Vec2 u, float axis_sign) {
  const float r = std::sqrt(u.x), phi = 2.0f * std::numbers::pi_v<float> * u.y;
  return {r * std::cos(phi), r * std::sin(phi), axis_sign * std::sqrt(std::fmax(0.0f, 1.0f - u.x))};
}

}  // namespace rimu::test
