#include "transport/integrators/irradiance_estimator.h"

#include <cmath>
#include <numbers>

#include "transport/geometry/frame.h"
#include "transport/integrators/shadow_passage.h"
#include "transport/sampling/direction_warps.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

// Next-event estimation at the receptor: Le T cos θ / q_light, weighted by the power heuristic against the cosine
// technique. The sums over lanes follow the integrator's (path_integrator.cpp): s = Σ_k R_k q_k, so with the
// receptor's wavelength-independent densities hero mode reduces to q_l² / (q_l² + q_c²).
SampledSpectrum IrradianceEstimator::light_sampled(const LightSamplingPoint& at, const SampledSpectrum& ratios,
                                                   const SampledWavelengths& lambda, Sampler& sampler) const {
  const float u_choice = sampler.next_1d();
  const Vec2 u_light = sampler.next_2d();
  if (settings_.direct_lighting == DirectLighting::bsdf_only) return SampledSpectrum(0.0f);
  const auto pick = scene_.light_sampler->sample(at, u_choice);
  if (!pick) return SampledSpectrum(0.0f);
  const Light& light = *(*scene_.lights)[size_t(pick->light)];
  const LightReference reference{at.position_m, at.normal};
  const auto ls = light.sample_part_li(pick->part, reference, lambda, u_light);
  if (!ls) return SampledSpectrum(0.0f);
  const float cos_theta = dot(at.normal, ls->wi);
  if (!(cos_theta > 0.0f) || !(ls->pdf_solid_angle > 0.0f)) return SampledSpectrum(0.0f);

  Ray shadow;
  shadow.origin = offset_ray_origin(at.position_m, at.normal, ls->wi, scene_.scene_scale);
  const ShadowSegment segment = shadow_segment(shadow.origin, at.position_m, *ls, scene_.scene_scale);
  shadow.direction = segment.direction;
  shadow.t_max = std::isinf(segment.length) ? segment.length : segment.length * (1.0f - 0x1p-12f);
  const auto passage = trace_shadow(scene_, shadow, lambda);
  if (!passage) return SampledSpectrum(0.0f);

  const LaneTechniques lanes{settings_.wavelengths};
  const float sum_ratio = sum(ratios);
  const float s_light = pick->probability * ls->pdf_solid_angle * sum_ratio;
  const bool cosine_reaches = !ls->is_delta && settings_.direct_lighting != DirectLighting::nee_only;
  const float s_cosine =
      cosine_reaches ? sum(ratios * lanes.densities(Float4(cosine_hemisphere_pdf(cos_theta)) * passage->pass_probability))
                     : 0.0f;
  const float weight = s_light / (s_light * s_light + s_cosine * s_cosine);
  return ratios * ls->radiance * passage->transmittance * Float4(cos_theta * float(kLaneCount) * weight);
}

SampledSpectrum IrradianceEstimator::irradiance(Vec3 position_m, Vec3 normal, const SampledWavelengths& lambda,
                                                Sampler& sampler) const {
  const LaneTechniques lanes{settings_.wavelengths};
  const SampledSpectrum ratios = lanes.initial_ratios();
  const LightSamplingPoint at{position_m, normal, &lambda};
  SampledSpectrum irradiance = light_sampled(at, ratios, lambda, sampler);

  // The cosine technique: E = π L(ω) for ω drawn with density cos θ/π.
  const Frame frame = Frame::from_normal(normal);
  const Vec3 wi = frame.to_world(sample_cosine_hemisphere(sampler.next_2d()));
  const float cos_theta = dot(wi, normal);
  if (!(cos_theta > 0.0f)) return irradiance;
  Ray ray;
  ray.origin = offset_ray_origin(position_m, normal, wi, scene_.scene_scale);
  ray.direction = wi;
  const PathStartVertex start{cosine_hemisphere_pdf(cos_theta), LightReference{position_m, normal}, at};
  irradiance += radiance_from_vertex(scene_, settings_, ray, lambda, sampler, start) * Float4(std::numbers::pi_v<float>);
  return irradiance;
}

}  // namespace rimu
