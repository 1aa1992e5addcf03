// Metropolis light transport in primary sample space (Kelemen et al. 2002) over the path tracer: the render loop
// for `"integrator": {"method": "metropolis"}`.
#pragma once

#include <functional>

#include "render/camera/camera.h"
#include "render/film/film.h"
#include "render/film/pixel_filter.h"
#include "render/renderer.h"
#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/geometry/ray.h"
#include "transport/integrators/caustic_light_tracer.h"
#include "transport/integrators/metropolis_settings.h"
#include "transport/sampling/sampler.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

/// One sample's estimate for a camera ray: the integrator's radiance(ray, lambda, sampler), and what its light subpath
/// adds elsewhere on the film (bidirectional path tracing's light vertices seen by the camera; the path tracer adds
/// none), each as the render loop's light paths splat it (once per pixel of the film).
using CameraPathRadiance = std::function<SampledSpectrum(const Ray& ray, const SampledWavelengths& lambda,
                                                         Sampler& sampler, std::vector<CausticSplat>& light_splats)>;

/// Renders spp × pixels mutations into `film`: each chain's samples are distributed by the brightness of their path
/// (the sum of the film channels' magnitudes), and each splats its channels divided by that brightness, times the
/// bootstrap's mean brightness b. The film position (2 dimensions over the film's pixel bounds), lens (2),
/// wavelengths and shutter time come first, as in the path tracer's samples. Splats are summed in 64-bit fixed
/// point, so the image does not depend on the order threads add them. Passes of 1, 2, 4, 8, 16, 16, … spp as in
/// render(); an interrupt keeps the passes completed.
RenderStatistics render_metropolis(const CameraPathRadiance& radiance, const MetropolisSettings& settings,
                                   WavelengthMode wavelengths, const TabulatedWavelengthDensity* wavelength_density,
                                   bool has_motion, const Camera& camera, const PixelFilter& filter, Film& film,
                                   const RenderOptions& options);

}  // namespace rimu
