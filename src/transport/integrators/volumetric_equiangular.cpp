// The equiangular technique of VolumetricPathIntegrator (Kulla & Fajardo 2012) and its MIS with free-flight
// sampling. The bookkeeping (docs/media.md, "Equiangular sampling"):
//
// On a homogeneous segment, the path prefix has throughput β = f/p(prefix|hero) and ratios R_k = p(prefix|λ_k)/
// p(prefix|hero). Two techniques produce a scattering point at distance s connected to a point y on a part ℓ of a
// light (a point light, a luminaire, an emitting triangle, a sphere):
//   distance: lane k as hero scatters at s with density p_k(s) (spectral_distance_sampling.h), then NEE picks ℓ
//     with P_n(ℓ | s) (the light sampler at s) and y with q(y | s) (the part's own light sampling; 1 for a point);
//   equiangular: picks ℓ with probability P_e(ℓ) (the light sampler at the segment's start), then s with density
//     p_e(s) (the same for all lanes) aimed at the part's centre (Light::emission_centre_m), then y as NEE at s
//     does, with q(y | s).
// q is a common factor of both densities: it cancels from the weights, which therefore depend on s and ℓ alone.
// Each path runs both, with a hero drawn uniformly among the four lanes, so the balance heuristic over the eight
// (hero, technique) pairs gives the equiangular sample the lane-j estimate
//   F_j / ((1/4) Σ_k p(prefix|λ_k) q (P_e p_e(s) + P_n p_k(s))) = 4 β_j g_j / (q (S_equi + S_dist)),
// F_j = f_j(prefix)·g_j the path's contribution, g_j that of the last segment and the light connection, and
//   S_equi = P_e(ℓ) p_e(s) Σ_k R_k,   S_dist = P_n(ℓ | s) Σ_k R_k p_k(s)   (R before the flight; with a light
// sampler that ignores the point, P_e = P_n and it cancels).
// A light with area is also reached by the phase function's sampled direction from the scattering point. The
// distance technique's two estimates (NEE and the direction that hits the light), weighted against each other as
// at any vertex, are both multiplied by w_d = S_dist / (S_dist + S_equi) and the equiangular one has w_e = 1 − w_d:
// the weights of the three sum to w_d (w_nee + w_dir) + w_e = 1 for every path, so the sum stays unbiased. For
// lights at infinity (no centre) p_e = 0: w_d = 1 and the estimator is the one without equiangular sampling.
#include <cmath>

#include "transport/integrators/volumetric_path_integrator.h"

namespace rimu {

VolumetricPathIntegrator::VolumetricPathIntegrator(const VolumetricScene& scene, VolumetricIntegratorSettings settings)
    : scene_(scene), settings_(settings) {
  settings_.distance = distance_sampling_for(settings.distance, settings.path.wavelengths);
  for (const auto& light : *scene_.surfaces.lights)
    if (equiangular_centre_m(*light, -1)) has_equiangular_lights_ = true;
  for (const Medium& medium : *scene_.media)
    if (uses_tracking(medium, settings_.distance)) shadow_reads_throughput_ = true;
}

bool VolumetricPathIntegrator::uses_equiangular(const Medium& medium) const {
  return has_equiangular_lights_ && medium.homogeneous() != nullptr &&
         settings_.distance != DistanceSampling::spectral_tracking &&
         settings_.path.direct_lighting != DirectLighting::bsdf_only;
}

SampledSpectrum VolumetricPathIntegrator::equiangular_direct(EquiangularSegment segment, const Medium& medium,
                                                             const SampledSpectrum& beta,
                                                             const SampledSpectrum& ratios, const MediumStack& stack,
                                                             const SampledWavelengths& lambda,
                                                             Sampler& sampler, int& light_group) const {
  const float u_light = sampler.next_1d(), u_t = sampler.next_1d();
  const Vec2 u_position = sampler.next_2d();
  const LightSampler& light_sampler = *scene_.surfaces.light_sampler;
  const auto pick = light_sampler.sample(equiangular_choice_point(segment), u_light);
  if (!pick) return Float4(0.0f);
  const Light& light = *(*scene_.surfaces.lights)[size_t(pick->light)];
  light_group = light.light_group();
  const std::optional<Vec3> centre_m = equiangular_centre_m(light, pick->part);
  if (!centre_m) return Float4(0.0f);  // the technique has density 0 for lights it does not aim at
  segment.light_m = *centre_m;
  const auto es = segment.sample(u_t);
  if (!es) return Float4(0.0f);
  const Vec3 point = segment.origin + segment.direction * es->t;
  // y as NEE at the point picks it within the part: q(y | s) (1 for a light at a point).
  const auto ls = light.sample_part_li(pick->part, {point, Vec3{}}, lambda, u_position);
  if (!ls || !(ls->pdf_solid_angle > 0.0f)) return Float4(0.0f);

  // T_j(s) σ_s,j: the segment's contribution up to a scattering event at s (exact for a homogeneous medium).
  const MediumCoefficients c = medium.homogeneous()->coefficients(lambda);
  const float s = es->t - segment.t0;
  const float phase = medium.phase().eval(-segment.direction, ls->wi);
  const SampledSpectrum throughput = beta * c.sigma_s_per_m * exp(-c.sigma_t_per_m() * Float4(s)) * Float4(phase);
  if (!(max_lane(throughput) > 0.0f)) return Float4(0.0f);
  const auto tr = shadow(point, ls->wi, ls->distance, segment.time, stack, lambda, throughput);
  if (!tr) return Float4(0.0f);

  const float s_equi = pick->probability * es->pdf_per_m * sum(ratios);
  // The choice next-event estimation makes at a medium point: with the path's wavelengths, as there.
  const float s_dist = light_sampler.pmf({point, Vec3{}, &lambda}, pick->light, pick->part) *
                       distance_technique_density(c, settings_.distance, s, ratios);
  const float denominator = s_equi + s_dist;
  if (!(denominator > 0.0f)) return Float4(0.0f);
  return throughput * tr->transmittance * ls->radiance * Float4(float(kLaneCount) / (ls->pdf_solid_angle * denominator));
}

std::optional<Vec3> VolumetricPathIntegrator::equiangular_centre_m(const Light& light, int part) const {
  switch (settings_.equiangular) {
    case EquiangularLights::off:
      return std::nullopt;
    case EquiangularLights::points:
      return light.is_delta() ? light.emission_centre_m(part) : std::nullopt;
    case EquiangularLights::all:
      return light.emission_centre_m(part);
  }
  return std::nullopt;
}

float VolumetricPathIntegrator::distance_technique_weight(EquiangularSegment segment, const Medium& medium, float t,
                                                          Vec3 centre_m, const SampledSpectrum& ratios,
                                                          const SampledWavelengths& lambda, float nee_probability,
                                                          float equiangular_probability) const {
  segment.light_m = centre_m;
  const float s_equi = equiangular_probability * segment.pdf(t) * sum(ratios);
  const float s_dist = nee_probability * distance_technique_density(medium.homogeneous()->coefficients(lambda),
                                                                    settings_.distance, t - segment.t0, ratios);
  // Both densities underflowed: the equiangular estimate carries nothing here either, so the event keeps it all.
  return s_dist + s_equi > 0.0f ? s_dist / (s_dist + s_equi) : 1.0f;
}

}  // namespace rimu
