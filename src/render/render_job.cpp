#include "render/render_job.h"

#include <cmath>
#include <cstdio>
#include <chrono>
#include <ctime>
#include <ostream>
#include <sstream>

#include "render/film/camera_colour_matrix.h"
#include "render/camera/camera_keyframes.h"
#include "render/camera/camera_exposure.h"
#include "render/output/display_image_policy.h"
#include "render/output/display_output.h"
#include "render/output/exr_output.h"
#include "render/output/output_file.h"
#include "render/output/partial_exr.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene_frame.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"
#include "render/interrupt_flag.h"
#include "render/scene/json_cursor.h"
#include "render/progress_reporter.h"
#include "render/scene/scene.h"

namespace rimu {
namespace {

PixelFilter make_filter(const FilterSettings& f) {
  if (f.type == "box") return PixelFilter::box(f.radius_px);
  if (f.type == "blackman-harris") return PixelFilter::blackman_harris(f.radius_px);
  return PixelFilter::gaussian(f.radius_px, f.sigma_px);
}

// "--film" is either a response (xyz, xyz10, camera:<name>) or spectral:<bins> (XYZ plus a spectral framebuffer).
void apply_film_option(const std::string& film, RenderSettings& settings) {
  if (film.rfind("spectral:", 0) == 0) {
    int bins = 0;
    try {
      size_t used = 0;
      bins = std::stoi(film.substr(9), &used);
      if (used != film.size() - 9) bins = 0;
    } catch (const std::exception&) {
      bins = 0;
    }
    if (bins < 1 || bins > 471)
      throw InputError({"", 0, "--film"}, "spectral:<bins> needs a bin count in 1-471, got '" + film + "'");
    settings.spectral_bins = bins;
    return;
  }
  settings.film_response = film;
}

bool has_camera_options(const RenderJob& job) {
  return job.iso || job.shutter_s || job.f_number || job.compensation_ev;
}

// --iso, --shutter, --f-number, --ev, --white-balance over the scene camera's exposure and white balance. Each is
// held to the range the scene's key accepts (camera_exposure.h).
void apply_camera_options(const RenderJob& job, CameraExposureSettings& camera, SpectralLibrary& library) {
  if (has_camera_options(job)) {
    PhysicalCameraSettings e = camera.exposure.value_or(PhysicalCameraSettings{});
    if (job.iso) check_camera_option(e.iso = *job.iso, kIsoRange, "--iso");
    if (job.shutter_s) check_camera_option(e.shutter_s = *job.shutter_s, kShutterRange_s, "--shutter");
    if (job.f_number) check_camera_option(e.f_number = *job.f_number, kFNumberRange, "--f-number");
    if (job.compensation_ev)
      check_camera_option(e.exposure_compensation_ev = *job.compensation_ev, kCompensationRange_ev, "--ev");
    camera.exposure = e;
  }
  if (job.white_balance)
    camera.white_balance = parse_white_balance_option(*job.white_balance, library, "--white-balance");
}

// The outputs, checked before anything slow happens: -o is OpenEXR and must say so, --png picks its format by its
// extension, the two are different files, and a file can be created in each folder.
void check_outputs(const RenderJob& job) {
  if (lower_case_extension(job.exr_output) != "exr")
    throw InputError({job.exr_output.string(), 0, "-o"},
                     "the scene-referred OpenEXR image needs a name ending in .exr (got '" +
                         job.exr_output.extension().string() + "'); a display image (.png, .jpg, .tif) is --png");
  if (job.png_output) {
    if (same_output_file(job.exr_output, *job.png_output))
      throw InputError({job.png_output->string(), 0, "--png"},
                       "-o and --png name the same file; the display image would replace the OpenEXR image");
    display_image_format(*job.png_output, "--png");
  }
  check_output_path(job.exr_output);
  if (job.png_output) check_output_path(*job.png_output);
}

// No output may be a file the render reads: the scene, or a file loading it read (a mesh, a texture, a spectrum,
// an Include), also through a link — the list is the readers' own (InputFileLog), not a guess from the scene's
// text. Checkpoints are written to -o, so they are covered too.
void check_outputs_not_inputs(const RenderJob& job, const std::vector<std::filesystem::path>& files_read) {
  std::vector<InputFile> inputs;
  for (const std::filesystem::path& file : files_read) inputs.push_back({file, "read by the scene"});
  check_output_not_input(job.exr_output, "-o", inputs);
  if (job.png_output) check_output_not_input(*job.png_output, "--png", inputs);
}

}  // namespace

std::pair<int, int> parse_resolution(const std::string& text, const std::string& option) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1 ||
      w > 32768 || h > 32768)
    throw InputError({"", 0, option}, "expected WIDTHxHEIGHT with both in 1-32768, e.g. 640x480; got '" + text + "'");
  return {w, h};
}

PixelBounds parse_crop(const std::string& text, const std::string& option) {
  PixelBounds b{};
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &b.x0, &b.y0, &b.x1, &b.y1, &extra) != 4 || b.x0 < 0 || b.y0 < 0 ||
      b.x1 <= b.x0 || b.y1 <= b.y0)
    throw InputError({"", 0, option}, "expected x0,y0,x1,y1 (pixels, end exclusive, x1 > x0, y1 > y0); got '" + text + "'");
  return b;
}

nlohmann::json read_pbrt_scene(const std::filesystem::path& path, SpectralLibrary& library, bool strict, std::ostream& log,
                               std::vector<PbrtOrigin>* origins) {
  PbrtImport imported = import_pbrt(path, library, {strict, {}});
  log << describe_ignored(imported.ignored);
  if (origins) *origins = std::move(imported.origins);
  return std::move(imported.document);
}

namespace {

// The job's scene loaded as a render loads it (the pbrt import or the JSON text with its frame, the job's
// integrator options, load_scene with errors moved to their pbrt lines), and the hash of what that read: every
// file the readers opened, recorded as they read it (InputFileLog), so the hash covers exactly the bytes the scene
// is made of. `library` must be fresh (nothing read through it yet), so its cache hides no read.
struct JobScene {
  nlohmann::json document;
  std::unique_ptr<Scene> scene;
  std::string hash;
  std::vector<std::filesystem::path> files_read;  ///< every file the load read, the scene file first
};

JobScene load_job_scene(const RenderJob& job, const std::filesystem::path& scene_path, SpectralLibrary& library,
                        std::ostream& log) {
  JobScene loaded;
  const InputFileLog files;
  // pbrt-v4 files are translated into a JSON document first; both then go through the same loader.
  const bool pbrt = is_pbrt_scene_path(scene_path);
  if (pbrt && job.frame)
    throw InputError({"", 0, "--frame"}, "frame numbers are substituted into JSON scenes; a pbrt-v4 scene is read as it is");
  std::vector<PbrtOrigin> pbrt_origins;  // errors inside files a pbrt scene names are reported at its lines
  loaded.document = pbrt ? read_pbrt_scene(scene_path, library, job.strict, log, &pbrt_origins)
                         : parse_json_text(scene_text_for_frame(scene_path, job.frame), scene_path.string());
  nlohmann::json& document = loaded.document;
  if (job.frame) apply_camera_keyframes(document, *job.frame, scene_path.string());  // a camera path keyed by frame
  if (job.wavelengths) document["integrator"]["wavelengths"] = wavelength_mode_name(*job.wavelengths);
  if (job.wavelength_density)
    document["integrator"]["wavelength_density"] =
        *job.wavelength_density == WavelengthDensityKind::lights ? "lights" : "visible";
  if (job.light_sampler) document["integrator"]["light_sampler"] = light_sampler_kind_name(*job.light_sampler);
  if (job.guiding) document["integrator"]["guiding"] = *job.guiding;
  try {
    loaded.scene = load_scene(document, scene_path.string(), scene_path.parent_path(), library);
  } catch (const InputError& e) {
    if (std::optional<InputError> at_pbrt = at_pbrt_origin(e, pbrt_origins)) throw *at_pbrt;
    throw;
  }
  loaded.hash = scene_hash_of_files(files, scene_path, library.root(), job);
  loaded.files_read.push_back(scene_path);
  for (const auto& [path, digest] : files.files()) loaded.files_read.push_back(path);
  return loaded;
}

// The render itself. `previous`: a partial (checkpoint) of this job whose sums the film starts from; the render
// continues after its last sample.
RenderJobResult render_job(const RenderJob& job, const PartialImage* previous, InterruptFlag& interrupt,
                           std::ostream& log) {
  // Everything that can be checked without the scene is checked first: a typo costs nothing.
  check_outputs(job);
  DisplayOptions display;
  display.exposure_ev = job.exposure_ev;
  display.view = job.view;
  const DisplayTransform display_check(ResponseKind::cie_xyz, display);  // the view, the exposure, the config
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const std::filesystem::path scene_path = job.scene ? *job.scene : default_scene_path(library);
  JobScene loaded = load_job_scene(job, scene_path, library, log);
  check_outputs_not_inputs(job, loaded.files_read);
  const nlohmann::json& document = loaded.document;
  const std::unique_ptr<Scene>& scene = loaded.scene;
  const std::string& hash = loaded.hash;
  if (job.expected_scene_hash && *job.expected_scene_hash != hash)
    throw InputError({scene_path.string(), 0, ""},
                     "the scene (its file, the files it names, or image options) hashes to " + hash +
                         ", not the expected " + *job.expected_scene_hash + ": it changed after the render was submitted");
  if (previous && previous->record.scene_hash != hash)
    throw InputError({scene_path.string(), 0, ""},
                     "the scene (its file, the files it names, or image options) hashes to " + hash + ", but " +
                         previous->path.string() +
                         " was rendered from one that hashed to " + previous->record.scene_hash +
                         ": it changed since; resuming would mix two scenes");

  for (const std::string& warning : scene->warnings) log << "rimu: warning: " << warning << "\n";
  RenderSettings& settings = scene->settings;
  if (job.width) settings.width = *job.width;
  if (job.height) settings.height = *job.height;
  if (job.samples_per_pixel) settings.samples_per_pixel = *job.samples_per_pixel;
  if (job.seed) settings.seed = *job.seed;
  if (job.sampler) settings.sampler = *job.sampler;
  if (job.film) apply_film_option(*job.film, settings);
  apply_camera_options(job, settings.camera_exposure, library);

  FilmOptions film_options{settings.width, settings.height, std::nullopt, settings.spectral_bins};
  // --crop, else the scene's film "crop" (checked against the scene's resolution, which --width/--height may change).
  if (const std::optional<PixelBounds> crop = job.crop ? job.crop : settings.crop) {
    if (crop->x1 > settings.width || crop->y1 > settings.height)
      throw InputError({job.crop ? "" : scene_path.string(), 0, job.crop ? "--crop" : "/film/crop"},
                       "the crop window reaches outside the " + std::to_string(settings.width) + "x" +
                           std::to_string(settings.height) + " image");
    film_options.crop = *crop;
  }
  SpectralResponse response = [&] {
    try {
      // Rgb transport's lanes are linear sRGB, not wavelengths: its film converts them with the sRGB matrix.
      if (settings.integrator.wavelengths == WavelengthMode::rgb) {
        if (settings.film_response != "xyz") throw InputError({}, "rgb transport renders to an XYZ film only");
        return SpectralResponse::rgb_transport(library);
      }
      return SpectralResponse::from_spec(library, settings.film_response);
    } catch (const InputError& e) {
      throw InputError({"", 0, job.film ? "--film" : scene_path.string() + ": /film/response"}, e.explanation());
    }
  }();
  Film film(film_options, std::move(response));
  if (settings.camera_exposure.exposure) {
    try {
      film_exposure_scale(*settings.camera_exposure.exposure, film.response());
    } catch (const InputError& e) {
      throw InputError({"", 0, has_camera_options(job) ? "--iso/--shutter/--f-number/--ev"
                                                       : scene_path.string() + ": /camera/exposure"},
                       e.explanation());
    }
  }
  // Exposure and white balance reach the EXR and the PNG through the film's output transform (one place).
  const FilmOutputTransform output_transform = [&] {
    try {
      return film_output_transform(settings.camera_exposure, film.response(), library);
    } catch (const InputError& e) {
      throw InputError({"", 0, job.white_balance ? "--white-balance" : scene_path.string() + ": /camera/white_balance"},
                       e.explanation());
    }
  }();
  film.set_output_transform(output_transform);
  const PixelFilter filter = make_filter(settings.filter);
  std::optional<CameraColourFit> colour_fit;
  if (film.response().kind() == ResponseKind::camera_rgb) colour_fit = fit_camera_to_xyz(film.response(), library);
  const bool metered_display = !settings.camera_exposure.exposure && uses_photometric_units(document);

  // The samples this job covers: all of them, or a --samples range of a render of samples_per_pixel.
  const int total_spp = settings.samples_per_pixel;
  const SampleRange requested = job.samples.value_or(SampleRange{0, total_spp});
  if (requested.end > total_spp)
    throw InputError({"", 0, "--samples"}, "--samples " + requested.text() + " reaches beyond the render's " +
                                               std::to_string(total_spp) +
                                               " samples per pixel (the scene's samples_per_pixel, or --spp)");
  const bool partial_output = job.samples || job.checkpoint_interval_s || previous;
  int start = requested.begin;
  double previous_seconds = 0.0;
  if (previous) {
    if (previous->crop != film.pixel_bounds() || previous->spectral_bins != film.binning().count)
      throw InputError({previous->path.string(), 0, ""}, "its window or spectral bins differ from its recorded job's");
    start = previous->record.samples.front().end;
    previous_seconds = previous->metadata.render_time_s;
    add_partial_to_film(*previous, film);
  }

  const uint64_t total = uint64_t(film.pixel_bounds().area()) * uint64_t(requested.end - start);
  ProgressReporter::Options progress_options;
  progress_options.silent = job.quiet;  // --quiet: nothing on stderr but warnings and errors
  ProgressReporter progress(total, "rendering", progress_options);

  RenderOptions options;
  options.samples_per_pixel = requested.end;
  options.first_sample = start;
  options.threads = job.threads.value_or(0);
  options.seed = settings.seed;
  options.sampler = settings.sampler;
  options.interrupt = &interrupt;
  options.progress = &progress;
  const auto render_start = std::chrono::steady_clock::now();
  // The output after samples [requested.begin, reached) (a checkpoint, or the final image).
  auto exr_options = [&](int reached, bool interrupted) {
    ExrOptions exr;
    exr.pixel_type = job.half_exr ? ExrPixelType::half : ExrPixelType::float32;
    exr.metadata.samples_per_pixel = reached - requested.begin;
    exr.metadata.seed = settings.seed;
    exr.metadata.render_time_s =
        previous_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
    exr.metadata.interrupted = interrupted;
    exr.metadata.scene = scene_path.string();
    exr.metadata.extra["degenerateTrianglesRemoved"] = std::to_string(scene->degenerate_triangles_removed);
    exr.metadata.extra["wavelengths"] = wavelength_mode_name(settings.integrator.wavelengths);
    exr.metadata.extra["wavelengthDensity"] = scene->wavelength_density ? "lights" : "visible";
    exr.metadata.extra["sampler"] = sampler_kind_name(settings.sampler);
    exr.metadata.extra["lightSampler"] = light_sampler_kind_name(settings.light_sampler);
    exr.metadata.extra["guiding"] = settings.integrator.guiding ? "on" : "off";
    for (const auto& [key, value] : exposure_metadata(settings.camera_exposure, output_transform))
      exr.metadata.extra[key] = value;
    exr.metadata.camera = settings.camera_exposure.exposure;
    exr.metadata.finished_at = std::time(nullptr);
    if (colour_fit) {
      // The written R, G, B are M_wb · raw (times the exposure): undo the white balance to reach the fit's raw input.
      exr.metadata.camera_to_xyz = colour_fit->camera_to_xyz * output_transform.channel_matrix.inverse();
      exr.metadata.camera_to_xyz_mean_delta_e2000 = colour_fit->mean_delta_e2000;
    }
    if (partial_output) {
      PartialRecord record;
      record.scene_hash = hash;
      record.seed = settings.seed;
      if (reached > requested.begin) record.samples = {SampleRange{requested.begin, reached}};
      record.requested = requested;
      record.total_spp = total_spp;
      record.film_spec = settings.integrator.wavelengths == WavelengthMode::rgb ? "rgb-transport" : settings.film_response;
      record.output_transform = output_transform;
      RenderJob recorded = job;
      recorded.samples = requested;
      recorded.samples_per_pixel = total_spp;
      recorded.seed = settings.seed;
      record.job = render_job_json(recorded);
      exr.partial = record;
    }
    return exr;
  };
  auto last_checkpoint = render_start;
  if (job.checkpoint_interval_s) {
    options.after_pass = [&](int reached) {
      const auto now = std::chrono::steady_clock::now();
      if (reached >= requested.end || std::chrono::duration<double>(now - last_checkpoint).count() <
                                          *job.checkpoint_interval_s)
        return;
      const ExrOptions exr = exr_options(reached, false);
      write_exr(job.exr_output, film, exr);
      last_checkpoint = std::chrono::steady_clock::now();
      if (!job.quiet) log << "\nrimu: checkpoint " << job.exr_output.string() << ": samples " << requested.begin << ":"
                          << reached << "\n";
    };
  }
  RenderJobResult result;
  result.statistics = render(*scene, filter, film, options);
  progress.finish();
  result.sample_counts = film.sample_counts();
  const int reached = start + result.statistics.samples_per_pixel_done;

  const ExrOptions exr = exr_options(reached, result.statistics.interrupted);
  if (exr.pixel_type == ExrPixelType::half) {
    const std::string warning = half_range_warning(half_range_counts(film), job.exr_output.string());
    if (!warning.empty()) log << warning << "\n";
  }
  const size_t replaced = write_exr(job.exr_output, film, exr);
  if (replaced > 0)
    log << "rimu: warning: " << replaced << " values of " << job.exr_output.string()
        << " were NaN or beyond the largest float and were written as 0 or the largest value (see "
           "rimu:nonFiniteValuesReplaced); lower the exposure\n";
  if (job.png_output) {
    DisplayImagePolicy policy;
    policy.camera_fit = colour_fit;
    policy.white_balanced = settings.camera_exposure.white_balance.kind != WhiteBalanceSettings::Kind::none;
    policy.metered = metered_display;
    policy.quiet = job.quiet;
    policy.nits_per_unit_y =
        (colour_fit ? SpectralResponse::cie_xyz(library) : film.response()).luminance_nits_per_unit_y();
    write_policy_display_image(*job.png_output, film, display, policy, log);
  }

  const FilmSampleCounts& c = result.sample_counts;
  std::ostringstream summary;
  summary << "rimu: " << scene_path.string() << ": " << reached - requested.begin << " spp";
  if (job.samples || previous) summary << " (samples " << requested.begin << ":" << reached << ")";
  if (result.statistics.interrupted) summary << " (interrupted; requested " << requested.count() << ")";
  summary << " in " << result.statistics.seconds << " s, "
          << (result.statistics.seconds > 0 ? double(result.statistics.camera_samples) / result.statistics.seconds : 0.0)
          << " samples/s; discarded samples: " << c.nan << " NaN, " << c.infinite << " Inf, " << c.negative
          << " negative\n";
  if (const GuidingStatistics& g = result.statistics.guiding; g.active)
    summary << "rimu: path guiding: " << g.training_passes << " training passes, largest field " << g.spatial_leaves
            << " spatial leaves, " << g.directional_nodes << " directional nodes, "
            << double(g.memory_bytes) / (1024.0 * 1024.0) << " MiB\n";
  summary << "rimu: wrote " << job.exr_output.string();
  if (job.png_output) summary << " and " << job.png_output->string();
  summary << "\n";
  if (!job.quiet) log << summary.str();
  return result;
}

// --resume: the recorded job, continued from the file's sums.
RenderJobResult resume_render_job(const RenderJob& job, InterruptFlag& interrupt, std::ostream& log) {
  const PartialImage previous = read_partial_exr(*job.resume);
  RenderJob resumed = render_job_from_json(previous.record.job, job.resume->string() + ": rimu:partial:job");
  resumed.threads = job.threads;
  resumed.quiet = job.quiet;
  resumed.exr_output = job.exr_output;
  if (job.checkpoint_interval_s) resumed.checkpoint_interval_s = job.checkpoint_interval_s;
  const SampleRange requested = previous.record.requested;
  const std::vector<SampleRange>& held = previous.record.samples;
  if (held.size() > 1 || (held.size() == 1 && held.front().begin != requested.begin))
    throw InputError({job.resume->string(), 0, "--resume"},
                     "holds samples " + sample_ranges_text(held) + ", not one range starting at " +
                         std::to_string(requested.begin) + " (a merge of partials): render the missing samples with "
                         "--samples and merge them instead");
  if (held.empty()) return render_job(resumed, nullptr, interrupt, log);
  if (held.front().end >= requested.end) {
    if (!job.quiet) log << "rimu: " << job.resume->string() << " already holds samples " << requested.text()
        << ": nothing to resume\n";
    return {};
  }
  return render_job(resumed, &previous, interrupt, log);
}

}  // namespace

std::string scene_hash(const RenderJob& job) {
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const std::filesystem::path scene_path = job.scene ? *job.scene : default_scene_path(library);
  std::ostringstream ignored_report;  // the import's report of what it ignores: printed by the render, not here
  return load_job_scene(job, scene_path, library, ignored_report).hash;
}

RenderJobResult run_render_job(const RenderJob& job_in, std::ostream& log) {
  // Ctrl-C and SIGTERM are caught from here on, before anything slow (reading the scene, building the BVH): a
  // signal while the scene loads stops the render before its first sample, and the output is still written (0
  // samples; a checkpoint then resumes from the start). Before this line (process start, ~10 ms) it kills.
  InterruptFlag interrupt;
  RenderJob job = job_in;
  // "${frame}" in the output names, as in the scene (render/scene/scene_frame.h).
  job.exr_output = substitute_frame(job.exr_output.string(), job.frame, "-o");
  if (job.png_output) job.png_output = substitute_frame(job.png_output->string(), job.frame, "--png");
  if (job.resume) return resume_render_job(job, interrupt, log);
  return render_job(job, nullptr, interrupt, log);
}

}  // namespace rimu
