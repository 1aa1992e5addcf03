// The stages of one render job, in the order render_job() in render_job.cpp calls them, and the state they hand
// on. Each stage is a short function; the work that belongs to a room is that room's (output checks and writing:
// render/output/render_outputs.h; resuming a partial: render/output/partial_exr.h; the scene: render/scene/).
// A new stage (a time budget, a preview) is a function here and a line in render_job(); what it needs to carry
// goes into RenderJobState.
#pragma once

#include <chrono>
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/film/adaptive_sampling.h"
#include "render/film/camera_colour_matrix.h"
#include "render/film/feature_buffers.h"
#include "render/film/film.h"
#include "render/film/pixel_filter.h"
#include "render/output/display_transform.h"
#include "render/output/partial_exr.h"
#include "render/render_job.h"
#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"

namespace rimu {

class InterruptFlag;

/// The job's scene loaded as a render loads it (the pbrt import or the JSON text with its frame, the job's
/// integrator options, load_scene with errors moved to their pbrt lines), and the hash of what that read: every
/// file the readers opened, recorded as they read it (InputFileLog), so the hash covers exactly the bytes the
/// scene is made of.
struct JobScene {
  nlohmann::json document;
  std::unique_ptr<Scene> scene;
  std::string hash;
  std::vector<std::filesystem::path> files_read;  ///< every file the load read, the scene file first
};

/// `library` must be fresh (nothing read through it yet), so its cache hides no read.
JobScene load_job_scene(const RenderJob& job, const std::filesystem::path& scene_path, SpectralLibrary& library,
                        std::ostream& log);

/// What a render job carries from one stage to the next. Each block is filled by the stage named above it.
struct RenderJobState {
  RenderJobState(const RenderJob& job, const PartialImage* previous, const DisplayOptions& display,
                 std::ostream& log);

  const RenderJob& job;
  const PartialImage* previous;  ///< --resume: the partial whose sums the film starts from; nullptr otherwise
  std::ostream& log;
  DisplayOptions display;  ///< the display image's view and exposure (checked before the scene is read)
  SpectralLibrary library;
  std::filesystem::path scene_path;

  // read_job_scene
  JobScene loaded;

  // set_up_film
  std::unique_ptr<Film> film;
  FilmOutputTransform output_transform;  ///< exposure and white balance, for the EXR, the PNG and a partial
  std::optional<PixelFilter> filter;
  std::optional<CameraColourFit> colour_fit;  ///< a camera film's fit to XYZ
  bool metered_display = false;

  // plan_samples
  int total_spp = 0;               ///< the whole render's samples per pixel
  SampleRange requested;           ///< the samples this job covers: all, or a --samples range
  int first_sample = 0;            ///< where this run starts: requested.begin, or where a resumed partial stopped
  double previous_seconds = 0.0;   ///< a resumed partial's render time
  bool partial_output = false;     ///< write the sums and the record (--samples, --checkpoint, --resume)
  /// --time, else the scene's integrator.time_limit_s: render whole passes until this much render time is spent
  /// (render/time_budget.h); total_spp is then the maximum
  std::optional<double> time_limit_s;
  std::unique_ptr<AdaptiveSampling> adaptive;  ///< --noise-threshold: which pixels still take samples
  std::unique_ptr<FeatureBuffers> features;    ///< --aov, --denoise: the denoiser's feature buffers
  AovSelection aovs;                           ///< the layers written: --aov, else the scene's film "aov"

  // check_job_sensors
  SensorSettings sensors;  ///< the scene's "sensors" (render/scene/scene_sensors.h)

  // render_samples
  std::chrono::steady_clock::time_point render_start;
  RenderJobResult result;
  int reached = 0;  ///< the end of the samples now in the film
  bool budget_spent = false;  ///< the render ended on its time budget (complete, with fewer than total_spp)
  bool converged = false;     ///< an adaptive render ended with every pixel below the noise threshold
  std::chrono::steady_clock::time_point last_preview;  ///< when --preview was last written
};

/// Everything that can be checked without the scene, first (a typo costs nothing): the outputs, the display
/// view and exposure. Returns the display options.
DisplayOptions check_job_without_scene(const RenderJob& job);
/// Reads the scene, checks its hash (against the expected one and a resumed partial's) and that no output is one
/// of the files it read, logs its warnings and applies the job's options over its settings.
void read_job_scene(RenderJobState& state);
/// The film (response, crop, camera exposure, white balance), the pixel filter and a camera film's colour fit.
void set_up_film(RenderJobState& state);
/// The sample range this run covers; for --resume, the film starts from the partial's sums.
void plan_samples(RenderJobState& state);
/// Renders, writing a checkpoint every --checkpoint seconds and the preview every --preview-interval; a time
/// budget ends it after the last whole pass that fits. Ctrl-C stops it after a whole pass.
void render_samples(RenderJobState& state, InterruptFlag& interrupt);
/// The EXR (with the partial record when the job is partial), the display image and the last preview.
void write_job_outputs(RenderJobState& state);
/// One line of time, speed and discarded samples, and the files written (nothing with --quiet).
void log_job_summary(const RenderJobState& state);
/// Before rendering (render_job_sensors.cpp): the sensors can be measured in this scene (render/sensors/), their
/// outputs can be written and are none of the scene's files; --sensors-only needs sensors.
void check_job_sensors(RenderJobState& state);
/// The scene's sensors, measured with the image's integrator, seed and sampler, written as CSV and JSON with a
/// summary line per grid (not for a --samples partial or an interrupted render, which would mix with others).
void measure_job_sensors(RenderJobState& state, InterruptFlag& interrupt);

}  // namespace rimu
