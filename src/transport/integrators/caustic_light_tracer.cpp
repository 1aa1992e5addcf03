#include "transport/integrators/caustic_light_tracer.h"

#include <algorithm>
#include <cmath>

#include "spectral/wavelengths/lanes.h"
#include "transport/geometry/frame.h"
#include "transport/integrators/adjoint_shading.h"
#include "transport/integrators/shadow_passage.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {
namespace {

// Whether a material can have a delta lobe (conservatively: every kind but the diffuse ones and hair, whose lobes
// are never delta; a conductor or dielectric may be smooth somewhere even with a roughness texture).
bool may_scatter_specularly(const Material& material) {
  const Material::Variant& m = material.variant();
  return !(std::holds_alternative<DiffuseMaterial>(m) || std::holds_alternative<DiffuseTransmissionMaterial>(m) ||
           std::holds_alternative<HairMaterial>(m));
}

}  // namespace

CausticLightTracer::CausticLightTracer(const TransportScene& scene, const PathIntegratorSettings& settings)
    : scene_(scene), settings_(settings) {
  // Without a surface that can scatter specularly there is no caustic to trace: no light path is drawn (the path
  // tracer, which then never reaches its state E D S⁺, keeps everything).
  if (std::none_of(scene.materials->begin(), scene.materials->end(), may_scatter_specularly)) return;
  std::vector<double> power;
  for (size_t i = 0; i < scene.lights->size(); ++i) {
    const Light& light = *(*scene.lights)[i];
    if (!traces(light)) continue;
    const double p = light.total_power_w(scene.scene_scale);
    if (!(p > 0.0) || !std::isfinite(p)) continue;
    traced_.push_back(int(i));
    power.push_back(p);
  }
  if (!traced_.empty()) by_power_.emplace(power);
}

void CausticLightTracer::trace(const SampledWavelengths& lambda, Sampler& sampler, float time,
                               const LightTracingCamera& camera, std::vector<CausticSplat>& splats) const {
  if (!by_power_) return;
  const float u_light = sampler.next_1d();
  const Vec2 u_position = sampler.next_2d(), u_direction = sampler.next_2d();
  const auto pick = by_power_->sample_discrete(u_light);
  const Light& light = *(*scene_.lights)[size_t(traced_[size_t(pick.index)])];
  const float choice = by_power_->probability(pick.index);
  const std::optional<EmissionSample> emission = light.sample_emission(pick.u_remapped, u_position, u_direction, lambda);
  if (!emission || !(choice > 0.0f)) return;

  const LaneTechniques lanes{settings_.wavelengths};
  SampledSpectrum pdf_ratio = lanes.initial_ratios();
  SampledSpectrum beta = pdf_ratio * emission->weight / Float4(choice);
  if (!(max_lane(beta) > 0.0f)) return;
  Ray ray;
  ray.origin = emission->normal == Vec3{} ? emission->origin_m
                                          : offset_ray_origin(emission->origin_m, emission->normal,
                                                              emission->direction, scene_.scene_scale);
  ray.direction = emission->direction;
  ray.time = time;

  int specular_vertices = 0, passages_since_vertex = 0;
  for (int guard = 0; guard < settings_.max_depth + kMaxShadowPassages * (settings_.max_depth + 1) + 1; ++guard) {
    const std::optional<SurfaceHit> hit = scene_.geometry->intersect(ray);
    if (!hit || hit->material < 0) return;
    const Material& material = (*scene_.materials)[size_t(hit->material)];
    const bool may_pass = material.passes_shadow_rays() && passages_since_vertex < kMaxShadowPassages;
    const Vec3 wo_world = -ray.direction;  // towards the light
    MaterialContext context = MaterialContext::at(*hit, wo_world);
    context.shading_normal = material.shading_normal(context);
    const Bsdf bsdf = material.bsdf(context, lambda);
    const BsdfFlags flags = bsdf.flags();
    // The path integrator's frame: opaque (two-sided) materials flipped to the side the light arrives from.
    Vec3 ns = context.shading_normal, ng = hit->geometric_normal;
    if (!flags.has_transmission && dot(wo_world, ng) < 0.0f) {
      ns = -ns;
      ng = -ng;
    }
    const Frame frame = Frame::from_normal(ns);
    const Vec3 wo = frame.to_local(wo_world);
    if (wo.z == 0.0f) return;

    // E y S⁺ L: y's non-delta component seen by the camera.
    if (specular_vertices > 0 && flags.has_non_delta) {
      const Vec2 u_lens = sampler.next_2d();
      if (const auto seen = camera.see(hit->position, time, u_lens)) {
        const Vec3 to_camera = seen->camera_position_m - hit->position;
        const float distance = length(to_camera);
        const Vec3 w_camera = distance > 0.0f ? to_camera / distance : Vec3{};
        const bool wrong_side = !flags.has_transmission && dot(w_camera, ng) <= 0.0f;
        if (distance > 0.0f && !wrong_side) {
          // f·|cos| towards the camera with the adjoint's shading factor, as at a specular vertex below.
          const SampledSpectrum f = bsdf.eval(wo, frame.to_local(w_camera));
          const float factor =
              std::fabs(dot(w_camera, ns)) * adjoint_shading_factor(wo_world, w_camera, ns, ng);
          if (max_lane(f) > 0.0f && factor > 0.0f) {
            Ray shadow;
            shadow.time = time;
            shadow.origin = offset_ray_origin(*hit, w_camera, scene_.scene_scale);
            shadow.direction = w_camera;
            shadow.t_max = length(seen->camera_position_m - shadow.origin) * (1.0f - 0x1p-12f);
            if (const auto passage = trace_shadow(scene_, shadow, lambda)) {
              const SampledSpectrum value = beta * f * passage->transmittance *
                                            Float4(factor * seen->importance * kLanes / sum(pdf_ratio));
              if (max_lane(value) > 0.0f) splats.push_back({seen->film_px, value, lambda, light.light_group()});
            }
          }
        }
      }
    }

    // The light path continues through delta lobes only: a non-delta one leaves the paths traced here (and a
    // surface without any ends it at once).
    if (!flags.has_delta) return;
    const float u_lobe = sampler.next_1d();
    const Vec2 u = sampler.next_2d();
    const std::optional<BsdfSample> bs = bsdf.sample(wo, u_lobe, u);
    if (!bs || !(bs->pdf[0] > 0.0f)) return;
    const Vec3 wi_world = frame.to_world(bs->wi);
    if (!flags.has_transmission && dot(wi_world, ng) <= 0.0f) return;
    const bool straight_through = may_pass && bs->wi.z * wo.z < 0.0f;
    if (!straight_through && !bs->is_delta) return;
    if (!straight_through && ++specular_vertices > settings_.max_depth - 1) return;
    // Flux is carried: the sample's radiance scaling 1/η'² is undone, and the adjoint's shading factor applied.
    const float scale = std::fabs(bs->wi.z) / bs->pdf[0] * bs->eta * bs->eta *
                        adjoint_shading_factor(wo_world, wi_world, ns, ng);
    beta *= bs->f * Float4(scale);
    pdf_ratio *= lanes.densities(bs->pdf) / Float4(bs->pdf[0]);
    lanes.keep_followed_lanes(bs->wavelength_dependent_direction, pdf_ratio, beta);
    if (!(max_lane(abs(beta)) > 0.0f) || !(sum(pdf_ratio) > 0.0f)) return;
    passages_since_vertex = straight_through ? passages_since_vertex + 1 : 0;
    ray.origin = offset_ray_origin(*hit, wi_world, scene_.scene_scale);
    ray.direction = straight_through ? ray.direction : wi_world;
    ray.t_min = 0.0f;
    ray.t_max = INFINITY;
  }
}

}  // namespace rimu
