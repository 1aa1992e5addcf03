// The render loop: tiles in parallel (oneTBB), passes of samples, interruptible, deterministic.
#pragma once

#include <cstdint>
#include <functional>

#include "render/film/film.h"
#include "render/film/pixel_filter.h"
#include "render/scene/scene.h"
#include "transport/sampling/sampler.h"

namespace rimu {

class AdaptiveSampling;
class FeatureBuffers;  // render/film/feature_buffers.h
class InterruptFlag;
class ProgressReporter;

struct RenderOptions {
  int samples_per_pixel = 16;  ///< the end (exclusive) of the sample indices taken: [first_sample, samples_per_pixel)
  /// The first sample index taken: > 0 for a partial render (--samples a:b) or a resumed one, whose film already
  /// holds the sums of the samples before it. Passes follow the global schedule (sample_pass_end), so the film
  /// reaches the same sums as a render that started at 0.
  int first_sample = 0;
  /// Called on the calling thread after every whole pass, with the end of the samples now in the film (the film is
  /// consistent there: checkpoints are written from it).
  std::function<void(int samples_end)> after_pass;
  /// Called on the calling thread before every pass of samples [first, first + count); false ends the render
  /// there, with whole passes only (a time budget, render/time_budget.h). Unset: every pass is rendered.
  std::function<bool(int first, int count)> start_pass;
  int threads = 0;           ///< 0 = every core
  uint64_t seed = 1;
  SamplerKind sampler = SamplerKind::sobol;  ///< where the random numbers come from (docs/sampling.md)
  const InterruptFlag* interrupt = nullptr;  ///< polled between tiles; the image keeps only whole passes
  ProgressReporter* progress = nullptr;      ///< counts camera samples
  /// Adaptive sampling (render/film/adaptive_sampling.h): each pixel takes the samples the caller planned for the
  /// pass (plan_pass, in start_pass), continuing its own sample indices, and the render ends when every pixel has
  /// stopped. The caller plans every pass in start_pass and updates it in after_pass; the renderer reports the rays
  /// each pixel's samples traced (add_rays), their cost. Null: every pixel takes every pass.
  AdaptiveSampling* adaptive = nullptr;
  /// Feature buffers for a denoiser (`--aov`, `--denoise`): when set, every camera sample also traces a feature ray
  /// (transport/integrators/path_features.h) with a sampler of its own, so the image is the same with or without
  /// them, and its beauty goes to the half buffer of its index's parity. Each pass's tiles are merged with the
  /// film's, so an interrupted pass is dropped from both. nullptr: no feature work at all.
  FeatureBuffers* features = nullptr;
};

/// What path guiding learned (docs/transport.md, "Path guiding"): the last field fitted, and its memory.
struct GuidingStatistics {
  bool active = false;      ///< the integrator was asked to guide (media scenes are not guided: false)
  int training_passes = 0;  ///< passes whose samples a field was fitted to
  size_t spatial_leaves = 0, directional_nodes = 0, memory_bytes = 0;  ///< of the largest field fitted
  size_t samples_recorded = 0;  ///< in the last training pass
};

struct RenderStatistics {
  int samples_per_pixel_done = 0;  ///< samples taken by this call; < requested if interrupted
  bool interrupted = false;
  bool stopped_by_start_pass = false;  ///< start_pass refused a pass (e.g. the time budget was spent)
  double seconds = 0;
  uint64_t camera_samples = 0;
  GuidingStatistics guiding;
  /// Caustics were light-traced (PathIntegratorSettings::caustic_light_tracing asked for it and the camera and
  /// sampling allow it; transport/integrators/caustic_light_tracer.h).
  bool caustic_light_tracing = false;
  /// Rendered by bidirectional path tracing (PathIntegratorSettings::bidirectional asked for it and the camera
  /// and sampling allow it; transport/integrators/bidirectional_path_integrator.h).
  bool bidirectional = false;
  /// Rendered by Metropolis light transport (PathIntegratorSettings::metropolis; render/metropolis_renderer.h).
  bool metropolis = false;
  /// With vertex merging (transport/integrators/vertex_merging.h): the last pass's radius and light vertices, and
  /// the most memory a pass's light vertices took.
  bool vertex_merging = false;
  float merge_radius_m = 0.0f;
  uint64_t merge_vertices = 0;
  uint64_t merge_light_subpaths = 0;  ///< per pass
  size_t merge_memory_bytes = 0;
};

/// Renders `scene` into `film` (which fixes resolution, crop and response). The result depends only on the
/// scene, the seed and the sample count: not on the thread count or the order in which tiles finish, because
/// every pixel's samples are drawn from (seed, pixel, sample index) and summed in sample order by one thread.
///
/// Samples are taken in passes of 1, 2, 4, 8, 16, 16, ... per pixel (sample indices [0,1), [1,3), [3,7), [7,15),
/// [15,31), ...: the pass boundaries depend on the sample index only, see sample_pass_end); an interrupt stops after the current
/// tile and throws away the unfinished pass, so every pixel of the result has the same number of samples.
RenderStatistics render(const Scene& scene, const PixelFilter& filter, Film& film, const RenderOptions& options);

/// Path guiding (PathIntegratorSettings::guiding) trains in the passes of the call: after the first pass, and then
/// after each pass that at least doubles the samples of the last fit, a field is fitted to every sample recorded so
/// far and guides the following passes (renderer.cpp, kGuidingSampleBudget; docs/transport.md, "Path guiding").
/// Fitting happens between passes on the calling thread, over the tiles' records in tile order: the image depends on
/// the seed and the samples asked for, not on the threads. A partial render (first_sample > 0) trains its own field
/// from its own passes.

/// The end of the pass that contains sample index `sample`: the smallest pass boundary above it (1, 3, 7, 15, then
/// every 16). A render of [a, b) cuts its passes at these boundaries (and at b), so a render resumed at a boundary
/// adds the same pass sums in the same order as an uninterrupted one: the film is bit-identical.
int sample_pass_end(int sample);

/// The same over a transport view and camera the caller assembles: for wrapping part of a scene, e.g. a ray
/// counter around `transport.geometry` (render/reports/ray_recorder.h). The overload above is this one with
/// scene.transport_view(), scene.settings.integrator and the scene's camera at its settings' resolution.
RenderStatistics render(const TransportScene& transport, const PathIntegratorSettings& integrator_settings,
                        const Camera& camera, const PixelFilter& filter, Film& film, const RenderOptions& options);
/// The same for a scene with participating media (transport/integrators/volumetric_path_integrator.h).
RenderStatistics render(const VolumetricScene& scene, const VolumetricIntegratorSettings& integrator_settings,
                        const Camera& camera, const PixelFilter& filter, Film& film, const RenderOptions& options);

}  // namespace rimu
