#include "transport/integrators/irradiance_estimator.h"

#include <cmath>

#include "transport/integrators/shadow_passage.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

// Next-event estimation at the receptor: Le T w / q_light, weighted by the power heuristic against the receptor's
// direction technique. The sums over lanes follow the integrator's (path_integrator.cpp): s = Σ_k R_k q_k, so with
// the receptor's wavelength-independent densities hero mode reduces to q_l² / (q_l² + q_d²).
SampledSpectrum IrradianceEstimator::light_sampled(const LightSamplingPoint& at, const MeterReceptor& receptor,
                                                   const SampledSpectrum& ratios, const SampledWavelengths& lambda,
                                                   Sampler& sampler) const {
  const float u_choice = sampler.next_1d();
  const Vec2 u_light = sampler.next_2d();
  if (settings_.direct_lighting == DirectLighting::bsdf_only) return SampledSpectrum(0.0f);
  const auto pick = scene_.light_sampler->sample(at, u_choice);
  if (!pick) return SampledSpectrum(0.0f);
  const Light& light = *(*scene_.lights)[size_t(pick->light)];
  const LightReference reference{at.position_m, at.normal};
  const auto ls = light.sample_part_li(pick->part, reference, lambda, u_light);
  if (!ls) return SampledSpectrum(0.0f);
  const float response = receptor.response(ls->wi);
  if (!(response > 0.0f) || !(ls->pdf_solid_angle > 0.0f)) return SampledSpectrum(0.0f);

  Ray shadow;
  const Vec3 lift = receptor.shape == MeterReceptor::Shape::plane ? at.normal : ls->wi;
  shadow.origin = offset_ray_origin(at.position_m, lift, ls->wi, scene_.scene_scale);
  const ShadowSegment segment = shadow_segment(shadow.origin, at.position_m, *ls, scene_.scene_scale);
  shadow.direction = segment.direction;
  shadow.t_max = std::isinf(segment.length) ? segment.length : segment.length * (1.0f - 0x1p-12f);
  const auto passage = trace_shadow(scene_, shadow, lambda);
  if (!passage) return SampledSpectrum(0.0f);

  const LaneTechniques lanes{settings_.wavelengths};
  const float sum_ratio = sum(ratios);
  const float s_light = pick->probability * ls->pdf_solid_angle * sum_ratio;
  const bool direction_reaches = !ls->is_delta && settings_.direct_lighting != DirectLighting::nee_only;
  const float s_direction =
      direction_reaches
          ? sum(ratios * lanes.densities(Float4(receptor.direction_pdf(ls->wi)) * passage->pass_probability))
          : 0.0f;
  const float weight = s_light / (s_light * s_light + s_direction * s_direction);
  return ratios * ls->radiance * passage->transmittance * Float4(response * float(kLaneCount) * weight);
}

SampledSpectrum IrradianceEstimator::irradiance(Vec3 position_m, const MeterReceptor& receptor,
                                                const SampledWavelengths& lambda, Sampler& sampler) const {
  const LaneTechniques lanes{settings_.wavelengths};
  const SampledSpectrum ratios = lanes.initial_ratios();
  const Vec3 normal = receptor.surface_normal();
  const LightSamplingPoint at{position_m, normal, &lambda};
  SampledSpectrum irradiance = light_sampled(at, receptor, ratios, lambda, sampler);

  // The direction technique: w(ω) L(ω) / p(ω) (for the plane, cos θ/(cos θ/π) = π).
  const Vec3 wi = receptor.sample_direction(sampler.next_2d());
  const float pdf = receptor.direction_pdf(wi), response = receptor.response(wi);
  if (!(pdf > 0.0f) || !(response > 0.0f)) return irradiance;
  Ray ray;
  const Vec3 lift = receptor.shape == MeterReceptor::Shape::plane ? normal : wi;
  ray.origin = offset_ray_origin(position_m, lift, wi, scene_.scene_scale);
  ray.direction = wi;
  const PathStartVertex start{pdf, LightReference{position_m, normal}, at};
  irradiance += radiance_from_vertex(scene_, settings_, ray, lambda, sampler, start) * Float4(response / pdf);
  return irradiance;
}

}  // namespace rimu
