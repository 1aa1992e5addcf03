#include "transport/integrators/daylit_connection.h"

#include <cmath>

#include "transport/bsdfs/material.h"
#include "transport/guiding/guiding_field.h"
#include "transport/integrators/path_integrator.h"
#include "transport/integrators/shadow_passage.h"

namespace rimu {

std::optional<DaylightEntry> enter_through_aperture(const TransportScene& scene,
                                                    const DaylightRaySampler::DaylightRay& daylight_ray,
                                                    const SampledWavelengths& lambda, float time) {
  // The ray starts a margin outside its aperture, so that a pane lying in the aperture's plane is on its inward
  // side, met once here and not again by the test towards the light below (2⁻¹⁴ of the coordinates' magnitude:
  // sixteen times the surfaces' offset, offset_ray_origin).
  const float margin = std::fmax(max_component(abs(daylight_ray.origin)), 1e-4f * scene.scene_scale) * 0x1p-14f;
  const Vec3 start = daylight_ray.origin + daylight_ray.to_light * margin;
  Ray ray;
  ray.origin = start;
  ray.direction = -daylight_ray.to_light;
  ray.time = time;
  // Panes let the daylight ray through as they let shadow rays through. Their transmittance is taken here, for light
  // going the other way (towards the light, as a shadow ray from the point met would meet them): nothing else lies
  // between the start and that point, so the test towards the light only has to cover what lies beyond the start.
  DaylightEntry entry;
  const PaneWalk walk = pass_panes(scene, ray, daylight_ray.to_light, lambda, entry.passage);
  if (walk.end != PaneWalk::End::surface) return std::nullopt;
  entry.hit = *walk.surface;
  // Point → light = point → start (the panes above, nothing opaque) + start → light.
  Ray outward;
  outward.origin = start;
  outward.direction = daylight_ray.to_light;
  outward.t_max = INFINITY;
  outward.time = time;
  const std::optional<ShadowPassage> beyond = trace_shadow(scene, outward, lambda);
  // As many surfaces as one shadow ray may pass (kMaxShadowPassages), so that the techniques make the same paths.
  if (!beyond || entry.passage.surfaces + beyond->surfaces > kMaxShadowPassages) return std::nullopt;
  entry.passage.transmittance *= beyond->transmittance;
  entry.passage.pass_probability *= beyond->pass_probability;
  entry.passage.surfaces += beyond->surfaces;
  return entry;
}

std::optional<DaylitPoint> find_daylit_point(const TransportScene& scene, const DaylightRaySampler& daylight_rays,
                                             const PathIntegratorSettings& settings, const SampledWavelengths& lambda,
                                             const DaylightRaySampler::DaylightRay& daylight_ray, float time,
                                             const GuidingField* field) {
  const std::optional<DaylightEntry> entry = enter_through_aperture(scene, daylight_ray, lambda, time);
  if (!entry || entry->hit.material < 0) return std::nullopt;
  const SurfaceHit* hit = &entry->hit;
  const Material& material = (*scene.materials)[size_t(hit->material)];
  // A mix chooses its material by the direction it is seen from, which differs for every vertex connecting here:
  // mixes are left out of the technique (the path integrator leaves them out of its weights alike).
  if (material.is_stochastic_mix()) return std::nullopt;
  DaylitPoint y;
  y.hit = *hit;
  y.light = daylight_ray.light;
  y.to_light = daylight_ray.to_light;
  y.delta_light = daylight_ray.is_delta;
  y.density = daylight_rays.density(daylight_ray.light, hit->position, hit->geometric_normal, daylight_ray.to_light,
                               daylight_ray.direction_pdf);
  if (!(y.density > 0.0f) || !std::isfinite(y.density)) return std::nullopt;

  // The BSDF as a path arriving from the light's side would build it.
  MaterialContext context = MaterialContext::at(*hit, daylight_ray.to_light);
  context.shading_normal = material.shading_normal(context);
  y.bsdf.emplace(material.bsdf(context, lambda));
  const BsdfFlags flags = y.bsdf->flags();
  if (!flags.has_non_delta) return std::nullopt;
  y.transmissive = flags.has_transmission;
  Vec3 ns = context.shading_normal, ng = context.geometric_normal;
  if (!y.transmissive && dot(daylight_ray.to_light, ng) < 0.0f) {
    ns = -ns;
    ng = -ng;
  }
  y.frame = Frame::from_normal(ns);
  y.geometric_normal = ng;

  y.radiance = daylight_ray.radiance * entry->passage.transmittance;
  y.pass_to_light = entry->passage.pass_probability;

  // What next-event estimation at y counts for this light (path_integrator.cpp): the sampler's probability, times
  // the candidates where a glossy vertex resamples its light.
  const LightSamplingPoint at{hit->position, y.transmissive ? Vec3{} : ng, &lambda};
  const LightSampler& light_sampler = *scene.light_sampler;
  const int part = light_sampler.part_of_hit(0);
  const float choice = light_sampler.pmf(at, daylight_ray.light, part);
  // A delta sun's samples carry the density 1 by convention (its pdf_li is 0: BSDF sampling cannot reach it).
  y.light_pdf = daylight_ray.is_delta ? 1.0f
                                      : (*scene.lights)[size_t(daylight_ray.light)]->pdf_part_li(
                                            part, LightReference{hit->position, ng}, daylight_ray.to_light);
  const int candidates = flags.has_glossy ? settings.glossy_candidates_for(scene.lights->size()) : 1;
  y.light_choice = (candidates > 1 && choice < 1.0f ? float(candidates) : 1.0f) * choice;

  // Guided as a path's own vertex here would be (a daylit point is never a pane: pass_panes walked past those).
  if (settings.guiding && is_guidable(flags, false))
    if (const LeafGuide leaf = guide_leaf_at(field, hit->position, ng)) y.guide.emplace(leaf, hit->position);
  return y;
}

SampledSpectrum connect_to_daylit_point(const TransportScene& scene, const LaneTechniques& lanes,
                                        const ConnectingVertex& x, const DaylitPoint& y,
                                        const SampledWavelengths& lambda, float guiding_probability) {
  const SampledSpectrum none(0.0f);
  const Vec3 to_y = y.hit.position - x.hit.position;
  const float distance2 = dot(to_y, to_y);
  if (!(distance2 > 0.0f) || !std::isfinite(distance2)) return none;
  const Vec3 w = to_y / std::sqrt(distance2);
  // Opaque surfaces reflect only on the side they are seen from (x) and lit from (y).
  if (!x.transmissive && dot(w, x.geometric_normal) <= 0.0f) return none;
  if (!y.transmissive && dot(w, y.geometric_normal) >= 0.0f) return none;
  const Vec3 wi_x = x.frame.to_local(w);
  const SampledSpectrum f_x = x.bsdf.eval(x.wo, wi_x) * Float4(std::fabs(wi_x.z));
  if (!(max_lane(f_x) > 0.0f)) return none;
  const Vec3 wo_y = y.frame.to_local(-w), wi_y = y.frame.to_local(y.to_light);
  const SampledSpectrum f_y = y.bsdf->eval(wo_y, wi_y) * Float4(std::fabs(wi_y.z));
  if (!(max_lane(f_y) > 0.0f)) return none;
  // G_y: y's area per unit solid angle at x (x's cosine is in f_x).
  const float g_y = std::fabs(dot(y.hit.geometric_normal, w)) / distance2;
  if (!(g_y > 0.0f) || !std::isfinite(g_y)) return none;

  Ray shadow;
  shadow.time = x.time;
  shadow.origin = offset_ray_origin(x.hit, w, scene.scene_scale);
  const ShadowSegment segment = shadow_segment(shadow.origin, offset_ray_origin(y.hit, -w, scene.scene_scale), w);
  if (!(segment.length > 0.0f)) return none;
  shadow.direction = segment.direction;
  shadow.t_max = segment.length * (1.0f - 0x1p-12f);
  const std::optional<ShadowPassage> passage = trace_shadow(scene, shadow, lambda);
  if (!passage) return none;

  // The three techniques' densities of this path from x on (daylit_connection.h), in the same measure.
  const float s_daylit = sum(x.pdf_ratio) * y.density;
  const SampledSpectrum to_y_densities =
      x.pdf_ratio * lanes.densities(x.sampling.pdf(x.wo, wi_x) * passage->pass_probability) * Float4(g_y);
  const float s_light = sum(to_y_densities) * y.light_choice * y.light_pdf;
  float s_bsdf = 0.0f;
  if (!y.delta_light) {
    const GuidedBsdf y_sampling(*y.bsdf, y.frame, y.guide ? &*y.guide : nullptr, guiding_probability);
    s_bsdf = sum(to_y_densities * lanes.densities(y_sampling.pdf(wo_y, wi_y) * y.pass_to_light));
  }
  const float weight = s_daylit / (s_light * s_light + s_daylit * s_daylit + s_bsdf * s_bsdf);
  if (!std::isfinite(weight)) return none;
  return f_x * passage->transmittance * f_y * y.radiance * Float4(g_y * float(kLanes) * weight);
}

}  // namespace rimu
