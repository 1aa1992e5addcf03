// Paths that start on a scattering vertex the caller sampled rather than at a camera: an illuminance meter's
// receptor (transport/integrators/irradiance_estimator.h) continues the path integrator from there.
#pragma once

#include "transport/integrators/path_integrator.h"

namespace rimu {

/// The first ray left `reference` in a direction drawn with density `direction_pdf` (solid angle, the same at every
/// wavelength), so an emitter it hits is weighted by the power heuristic against next-event estimation from
/// `sampling_point`, exactly as after a bounce of the path integrator. The caller does next-event estimation at
/// that vertex itself.
struct PathStartVertex {
  float direction_pdf = 0.0f;
  LightReference reference;
  LightSamplingPoint sampling_point;
};

/// The radiance arriving at `start.reference` along `ray` (which leaves it), estimated by the path integrator with
/// `scene` and `settings` (unguided), its first emitter weighted as PathStartVertex says; lanes as
/// PathIntegrator::radiance's.
SampledSpectrum radiance_from_vertex(const TransportScene& scene, const PathIntegratorSettings& settings, const Ray& ray,
                                     const SampledWavelengths& lambda, Sampler& sampler, const PathStartVertex& start);

}  // namespace rimu
