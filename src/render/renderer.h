// The render loop: tiles in parallel (oneTBB), passes of samples, interruptible, deterministic.
#pragma once

#include <cstdint>

#include "render/film.h"
#include "render/pixel_filter.h"
#include "render/scene.h"
#include "transport/sampler.h"

namespace rimu {

class InterruptFlag;
class ProgressReporter;

struct RenderOptions {
  int samples_per_pixel = 16;
  int threads = 0;           ///< 0 = every core
  uint64_t seed = 1;
  SamplerKind sampler = SamplerKind::sobol;  ///< where the random numbers come from (docs/sampling.md)
  const InterruptFlag* interrupt = nullptr;  ///< polled between tiles; the image keeps only whole passes
  ProgressReporter* progress = nullptr;      ///< counts camera samples
};

struct RenderStatistics {
  int samples_per_pixel_done = 0;  ///< < requested if interrupted
  bool interrupted = false;
  double seconds = 0;
  uint64_t camera_samples = 0;
};

/// Renders `scene` into `film` (which fixes resolution, crop and response). The result depends only on the
/// scene, the seed and the sample count: not on the thread count or the order in which tiles finish, because
/// every pixel's samples are drawn from (seed, pixel, sample index) and summed in sample order by one thread.
///
/// Samples are taken in passes of 1, 2, 4, 8, 16, 16, ... per pixel; an interrupt stops after the current
/// tile and throws away the unfinished pass, so every pixel of the result has the same number of samples.
RenderStatistics render(const Scene& scene, const PixelFilter& filter, Film& film, const RenderOptions& options);

/// The same over a transport view and camera the caller assembles: for wrapping part of a scene, e.g. a ray
/// counter around `transport.geometry` (render/ray_recorder.h). The overload above is this one with
/// scene.transport_view(), scene.settings.integrator and the scene's camera at its settings' resolution.
RenderStatistics render(const TransportScene& transport, const PathIntegratorSettings& integrator_settings,
                        const Camera& camera, const PixelFilter& filter, Film& film, const RenderOptions& options);
/// The same for a scene with participating media (transport/volumetric_path_integrator.h).
RenderStatistics render(const VolumetricScene& scene, const VolumetricIntegratorSettings& integrator_settings,
                        const Camera& camera, const PixelFilter& filter, Film& film, const RenderOptions& options);

}  // namespace rimu
