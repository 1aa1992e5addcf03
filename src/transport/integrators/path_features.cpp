#include "transport/integrators/path_features.h"

#include <algorithm>
#include <cmath>

#include "transport/bsdfs/material.h"
#include "transport/geometry/frame.h"
#include "transport/integrators/path_integrator.h"
#include "transport/integrators/ray_queries.h"
#include "transport/integrators/volumetric_path_integrator.h"

namespace rimu {

namespace {

// The surface albedo of the medium a ray enters at `hit` through material `material`, if it has one.
const SpectralTexture* entered_surface_albedo(const VolumetricScene* media, const SurfaceHit& hit, Vec3 wo_world) {
  if (!media || hit.material < 0 || size_t(hit.material) >= media->boundaries->size()) return nullptr;
  const int inside = (*media->boundaries)[size_t(hit.material)].interior_medium;
  if (inside < 0 || dot(wo_world, hit.geometric_normal) <= 0.0f) return nullptr;  // not entering from outside
  return (*media->media)[size_t(inside)].surface_albedo();
}

}  // namespace

PathFeatures first_diffuse_features(const TransportScene& scene, Ray ray, const SampledWavelengths& lambda,
                                    Sampler& sampler, const VolumetricScene* media) {
  PathFeatures features;
  float travelled = 0.0f;
  for (int bounce = 0; bounce <= kMaxSpecularBounces; ++bounce) {
    const std::optional<SurfaceHit> hit = scene.geometry->intersect(ray);
    if (!hit) return features;
    travelled += hit->t;
    const Vec3 wo_world = -ray.direction;
    if (hit->material < 0) {
      // A light without a surface: it is seen, but has no albedo.
      features.normal = dot(wo_world, hit->geometric_normal) < 0.0f ? -hit->geometric_normal : hit->geometric_normal;
      features.depth = travelled;
      return features;
    }
    const Material& material = (*scene.materials)[size_t(hit->material)];
    MaterialContext context = MaterialContext::at(*hit, wo_world);
    context.shading_normal = material.shading_normal(context);
    const Bsdf bsdf = material.bsdf(context, lambda);
    const BsdfFlags flags = bsdf.flags();
    Vec3 ns = context.shading_normal, ng = context.geometric_normal;
    if (!flags.has_transmission && dot(wo_world, ng) < 0.0f) {
      ns = -ns;
      ng = -ng;
    }
    const Frame frame = Frame::from_normal(ns);
    const Vec3 wo = frame.to_local(wo_world);
    const float u_lobe = sampler.next_1d();
    const Vec2 u = sampler.next_2d();
    const std::optional<BsdfSample> bs = wo.z != 0.0f ? bsdf.sample(wo, u_lobe, u) : std::nullopt;
    if (flags.has_non_delta || !flags.has_delta) {
      features.normal = ns;
      features.depth = travelled;
      if (const SpectralTexture* albedo = entered_surface_albedo(media, *hit, wo_world);
          albedo && flags.has_transmission) {
        const SampledSpectrum a = albedo->evaluate_at(context, lambda);
        for (int j = 0; j < kLaneCount; ++j)
          features.albedo.set(j, std::isfinite(a[j]) ? std::clamp(a[j], 0.0f, 1.0f) : 0.0f);
        return features;
      }
      if (bs && bs->pdf[0] > 0.0f && !bs->is_delta) {
        const Vec3 wi_world = frame.to_world(bs->wi);
        // Opaque materials reflect only to the geometric front side, as the path integrator requires.
        if (flags.has_transmission || dot(wi_world, ng) > 0.0f) {
          const SampledSpectrum weight = bs->f * Float4(std::fabs(bs->wi.z) / bs->pdf[0]);
          for (int j = 0; j < kLaneCount; ++j)
            features.albedo.set(j, std::isfinite(weight[j]) && weight[j] > 0.0f ? weight[j] : 0.0f);
        }
      }
      return features;
    }
    // Only delta lobes: continue along the sampled one (reflection or refraction), as the camera path would.
    if (!bs || !(bs->pdf[0] > 0.0f)) return PathFeatures{};
    ray.origin = offset_ray_origin(*hit, frame.to_world(bs->wi), scene.scene_scale);
    ray.direction = normalize(frame.to_world(bs->wi));
    ray.t_min = 0.0f;
    ray.t_max = INFINITY;
  }
  return PathFeatures{};
}

}  // namespace rimu
