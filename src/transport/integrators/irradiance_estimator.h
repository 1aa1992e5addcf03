// What a lighting designer's meters read, estimated by the path integrator that renders the image: irradiance on a
// one-sided, cosine-corrected receptor (a lux meter's head) and radiance along a line of sight (a luminance meter).
#pragma once

#include "transport/integrators/meter_receptor.h"
#include "transport/integrators/path_integrator.h"
#include "transport/integrators/path_start_vertex.h"

namespace rimu {

/// Irradiance and radiance at points that are not on any surface (the receptor is not part of the scene: it casts
/// no shadow and reflects nothing).
///
/// Irradiance E(λ) = ∫_{H+} L(λ, ω) cos θ dω over the hemisphere on the receptor's normal side, from two techniques
/// combined by the power heuristic, as at a Lambertian vertex of the path integrator: next-event estimation (one
/// light chosen by the scene's light sampler, its shadow ray through panes) and a cosine-distributed direction
/// (density cos θ/π) whose incident radiance is the integrator's full path estimate, its first emitter weighted
/// against light sampling (radiance_from_vertex, path_start_vertex.h). Delta lights (point, spot) are reached by
/// next-event estimation alone.
///
/// The same two techniques serve the cylindrical receptors (meter_receptor.h): E = ∫ L w dω over the sphere, the
/// light sample weighted by w and the second technique drawing directions by MeterReceptor::sample_direction.
///
/// Dimension order per sample, after the caller's wavelengths: light choice (1), light position (2), receptor
/// direction (2), then the integrator's per-bounce dimensions.
class IrradianceEstimator {
 public:
  /// `scene` must outlive the estimator; it has no participating media (the surface integrator is used).
  IrradianceEstimator(const TransportScene& scene, PathIntegratorSettings settings)
      : scene_(scene), settings_(settings), integrator_(scene_, settings) {}

  /// E at `position_m` on the side of `normal` (unit), in W/(m²·nm) per lane, lanes weighted as
  /// PathIntegrator::radiance's (the mean over lanes of Eⱼ c(λⱼ)/p(λⱼ) is unbiased for ∫E c dλ).
  SampledSpectrum irradiance(Vec3 position_m, Vec3 normal, const SampledWavelengths& lambda, Sampler& sampler) const {
    return irradiance(position_m, MeterReceptor{MeterReceptor::Shape::plane, normal, {}}, lambda, sampler);
  }

  /// ∫ L w dω at `position_m` for `receptor`'s response w (plane, cylinder or semi-cylinder), lanes as above.
  SampledSpectrum irradiance(Vec3 position_m, const MeterReceptor& receptor, const SampledWavelengths& lambda,
                             Sampler& sampler) const;

  /// L arriving at `ray.origin` from `ray.direction` (a luminance meter looking along the ray), as a camera ray.
  SampledSpectrum radiance(const Ray& ray, const SampledWavelengths& lambda, Sampler& sampler) const {
    return integrator_.radiance(ray, lambda, sampler);
  }

 private:
  SampledSpectrum light_sampled(const LightSamplingPoint& at, const MeterReceptor& receptor,
                                const SampledSpectrum& ratios, const SampledWavelengths& lambda, Sampler& sampler) const;

  const TransportScene& scene_;
  PathIntegratorSettings settings_;
  PathIntegrator integrator_;
};

}  // namespace rimu
