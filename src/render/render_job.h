// One render from the command line's point of view: load, override, render, write. The `rimu` tool is a thin
// parser in front of run_render_job(); tests call it directly.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/film/film.h"
#include "render/output/aov_channels.h"
#include "render/output/partial_record.h"
#include "render/renderer.h"
#include "spectral/io/input_file.h"
#include "spectral/library/spectral_library.h"
#include "transport/lights/light_sampler.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

struct PbrtOrigin;  // render/scene/pbrt/pbrt_to_scene.h

struct RenderJob {
  std::optional<std::filesystem::path> scene;  ///< empty: the embedded Cornell box
  std::filesystem::path exr_output = "rimu.exr";
  std::optional<std::filesystem::path> png_output;
  std::optional<int> samples_per_pixel, threads, width, height;
  std::optional<uint64_t> seed;
  std::optional<SamplerKind> sampler;  ///< overrides the scene's "sampler"
  /// Overrides the scene's "integrator.wavelengths" (hero, single, independent, rgb). Applied before the scene is
  /// loaded, because rgb mode loads colours and lights as RGB rather than upsampling them.
  std::optional<WavelengthMode> wavelengths;
  /// Overrides "integrator.wavelength_density" (visible, lights); applied before loading, which builds the density.
  std::optional<WavelengthDensityKind> wavelength_density;
  /// Overrides "integrator.light_sampler" (bvh, bvh-spectral, power, uniform); applied before loading, which
  /// builds the sampler.
  std::optional<LightSamplerKind> light_sampler;
  /// Overrides "integrator.guiding" (`--guiding on|off`; docs/transport.md, "Path guiding").
  std::optional<std::string> guiding;  ///< "on", "off" or "mixture"
  /// Overrides "integrator.daylit_points" (`--daylit-points on|off|auto`; docs/transport.md, "Daylit points").
  std::optional<std::string> daylit_points;
  /// Overrides "integrator.caustics" (`--caustics path_tracing|light_tracing`; docs/transport.md, "Caustics by
  /// light tracing").
  std::optional<std::string> caustics;
  /// Overrides "integrator.method" (`--method path_tracing|bidirectional|vcm`; docs/transport.md, "Bidirectional
  /// path tracing", "Vertex connection and merging").
  std::optional<std::string> method;
  std::optional<std::string> film;  ///< xyz | xyz10 | camera:<name> | camera-xyz:<name> | spectral:<bins>
  /// Overrides film "max_sample_value" (`--max-sample-value`; docs/rendering.md, "Sample clamp").
  std::optional<double> max_sample_value;
  std::optional<PixelBounds> crop;
  /// Write the EXR's image channels as half floats (`--half`); 32-bit floats otherwise (render/output/exr_output.h).
  bool half_exr = false;
  double exposure_ev = 0.0;  ///< display exposure of the PNG only (see also compensation_ev)
  /// The physical camera (render/camera/camera_exposure.h); each overrides the scene camera's "exposure" field. Giving any
  /// of them to a scene without "exposure" turns the physical camera on, the others taking sunny-16 values
  /// (ISO 100, 1/100 s, f/16, 0 EV).
  std::optional<double> iso, shutter_s, f_number, compensation_ev;
  std::optional<std::string> white_balance;  ///< none | a temperature (2700, 2700K) | an illuminant name
  std::string view = "Standard";
  bool strict = false;  ///< a pbrt-v4 scene: anything Rimu would ignore is an error (docs/pbrt-import.md)
  bool quiet = false;  ///< nothing on the log but warnings and errors: no progress, no summary, no checkpoint notes

  /// Render only sample indices [begin, end) of every pixel (a partial: the EXR also holds the exact sums and the
  /// record a merge needs; docs/farm.md). samples_per_pixel is then the whole render's spp (default: the scene's),
  /// which a merge checks the partials cover.
  std::optional<SampleRange> samples;
  /// Write the output as a partial every this many seconds (atomically: a valid file at any moment), and on
  /// Ctrl-C/SIGTERM. Implies a partial output (the sums are kept), so --resume can continue it.
  std::optional<double> checkpoint_interval_s;
  /// Continue the partial or checkpoint at this path to the end of the range it was asked for, with the options it
  /// records (its scene must still hash the same). exr_output defaults to it; threads and quiet are this job's.
  std::optional<std::filesystem::path> resume;
  /// The scene hash the caller expects (a farm task checks the scene did not change after submission).
  std::optional<std::string> expected_scene_hash;
  /// Render whole passes until this much render time is spent (`--time`; overrides the scene's
  /// "integrator.time_limit_s"; render/time_budget.h). samples_per_pixel (--spp) is then the maximum; without --spp
  /// there is none (the scene's "spp" caps only its own time_limit_s). Not with `samples`.
  std::optional<double> time_limit_s;
  /// The display image written while rendering (`--preview`): after a pass once `preview_interval_s` have passed
  /// since the last one, and at the end, with the display transform and exposure of the final --png.
  std::optional<std::filesystem::path> preview_output;
  double preview_interval_s = 5.0;
  /// With noise_threshold: a false-colour heat map of each pixel's remaining error (`--preview-error`,
  /// render/output/error_heat_map.h), written with every preview and at the end.
  std::optional<std::filesystem::path> preview_error_output;
  /// Adaptive sampling (`--noise-threshold`; render/film/adaptive_sampling.h): a pixel stops taking samples once
  /// the relative standard error of its luminance is below this; samples_per_pixel is the maximum. Not with
  /// `samples` or `checkpoint_interval_s` (its half buffers are not in a partial).
  std::optional<double> noise_threshold;
  /// Feature layers written into the EXR (`--aov albedo,normal,depth,variance,halves` or `all`;
  /// render/output/aov_channels.h). Not with `samples`, `checkpoint_interval_s` or `resume`: the feature buffers live
  /// only in this process, as adaptive sampling's half buffers do.
  AovSelection aovs;
  /// Denoise the image before writing it (`--denoise`; render/denoise/): the EXR's beauty and the display image are
  /// denoised, the noisy beauty is kept as the EXR layer "noisy". Same restrictions as `aovs`.
  bool denoise = false;
  /// The frame number substituted for "${frame}" in the scene file's text (docs/scene-format.md, "Frames").
  std::optional<int> frame;

  /// The scene's "sensors" (docs/scene-format.md, "Sensors"): measured after the image, or alone (sensors_only,
  /// `--sensors-only`: no film, no EXR). Their CSV and JSON go to sensors_output + ".csv"/".json" (`--sensors-out`),
  /// by default beside the EXR ("render.exr" → "render.sensors.csv"); sensor_samples overrides "sensors.samples".
  bool sensors_only = false;
  std::optional<std::filesystem::path> sensors_output;
  std::optional<int> sensor_samples;
};

/// The hash of a render (64-bit FNV-1a, 16 hex digits): equal hashes mean the same render. It covers every file
/// reading the scene opened (the scene file, what it includes, meshes, spectra, images, IES profiles, voxel grids,
/// data tables), each by its name and exactly the bytes read, and the options that change the image. It loads the
/// scene as a render does to learn what that reads (a render computes it from its own load). InputError if the
/// scene cannot be loaded.
std::string scene_hash(const RenderJob& job);
/// The hash of the files in `files` (InputFileLog, input_file.h) and the job's image options. A file is named
/// relative to the scene's folder when inside it, relative to Rimu's data folder (`data_root`) when inside that,
/// else by its absolute path, so a moved scene folder or another installation keeps the hash. A file the log holds
/// without a digest (an image a library read) is read again here.
std::string scene_hash_of_files(const InputFileLog& files, const std::filesystem::path& scene_path,
                                const std::filesystem::path& data_root, const RenderJob& job);
/// The job's options as JSON (what a partial records for --resume) and back.
std::string render_job_json(const RenderJob& job);
RenderJob render_job_from_json(const std::string& json, const std::string& where);

struct RenderJobResult {
  RenderStatistics statistics;
  FilmSampleCounts sample_counts;
};

/// Runs the job: throws InputError for bad input (scene, options) before rendering starts, RenderError for
/// failures of the machine or a library. Ctrl-C stops the render; the image reached so far is still written.
/// A summary (time, samples/s, discarded samples) goes to `log`.
RenderJobResult run_render_job(const RenderJob& job, std::ostream& log);

/// Translates a pbrt-v4 file (render/scene/pbrt/pbrt_to_scene.h) and writes what was ignored to `log`.
nlohmann::json read_pbrt_scene(const std::filesystem::path& path, SpectralLibrary& library, bool strict, std::ostream& log,
                               std::vector<PbrtOrigin>* origins = nullptr);

/// Parses "WxH", "x0,y0,x1,y1": InputError naming `option` on malformed text.
std::pair<int, int> parse_resolution(const std::string& text, const std::string& option);
PixelBounds parse_crop(const std::string& text, const std::string& option);
/// Parses a sample clamp (`--max-sample-value`): a finite number in Film's clamp range; InputError naming `option` otherwise.
double parse_max_sample_value(const std::string& text, const std::string& option);

}  // namespace rimu
