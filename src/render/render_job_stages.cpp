#include "render/render_job_stages.h"

#include <chrono>
#include <ctime>
#include <ostream>
#include <sstream>

#include "render/camera/camera_exposure.h"
#include "render/film/render_size.h"
#include "render/denoise/denoise_film.h"
#include "render/interrupt_flag.h"
#include "render/output/aov_channels.h"
#include "render/output/display_image_policy.h"
#include "render/output/error_heat_map.h"
#include "render/output/exr_output.h"
#include "render/output/render_outputs.h"
#include "render/progress_reporter.h"
#include "render/scene/camera_keyframes.h"
#include "render/scene/json_cursor.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene_frame.h"
#include "render/time_budget.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {
namespace {

PixelFilter make_filter(const FilterSettings& f) {
  if (f.type == "box") return PixelFilter::box(f.radius_px);
  if (f.type == "blackman-harris") return PixelFilter::blackman_harris(f.radius_px);
  if (f.type == "triangle") return PixelFilter::triangle(f.radius_px);
  return PixelFilter::gaussian(f.radius_px, f.sigma_px);
}

// "--film" is either a response (xyz, xyz10, camera:<name>, camera-xyz:<name>) or spectral:<bins> (XYZ plus a spectral framebuffer).
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

// The scene's hash against the one the farm expects and the one a resumed partial was rendered from.
void check_scene_hash(const RenderJobState& s) {
  const std::string& hash = s.loaded.hash;
  if (s.job.expected_scene_hash && *s.job.expected_scene_hash != hash)
    throw InputError({s.scene_path.string(), 0, ""},
                     "the scene (its file, the files it names, or image options) hashes to " + hash +
                         ", not the expected " + *s.job.expected_scene_hash + ": it changed after the render was submitted");
  if (s.previous && s.previous->record.scene_hash != hash)
    throw InputError({s.scene_path.string(), 0, ""},
                     "the scene (its file, the files it names, or image options) hashes to " + hash + ", but " +
                         s.previous->path.string() +
                         " was rendered from one that hashed to " + s.previous->record.scene_hash +
                         ": it changed since; resuming would mix two scenes");
}

// --width, --height, --spp, --seed, --sampler, --film and the camera options over the scene's settings.
void apply_job_options(const RenderJob& job, RenderSettings& settings, SpectralLibrary& library) {
  if (job.width) settings.width = *job.width;
  if (job.height) settings.height = *job.height;
  if (job.samples_per_pixel) settings.samples_per_pixel = *job.samples_per_pixel;
  if (job.seed) settings.seed = *job.seed;
  if (job.sampler) settings.sampler = *job.sampler;
  if (job.film) apply_film_option(*job.film, settings);
  apply_camera_options(job, settings.camera_exposure, library);
}

// --crop, else the scene's film "crop" (checked against the scene's resolution, which --width/--height may change)
// or "crop_window" (fractions, turned into pixels at the render's resolution).
FilmOptions film_options(const RenderJobState& s) {
  const RenderSettings& settings = s.loaded.scene->settings;
  FilmOptions options{settings.width, settings.height, std::nullopt, settings.spectral_bins};
  if (!s.job.crop && settings.crop_window) {
    // Fractions of whatever resolution the render uses (the scene's, or --resolution's).
    const PixelBounds pixels = settings.crop_window->pixels(settings.width, settings.height);
    if (pixels.empty())
      throw InputError({s.scene_path.string(), 0, "/film/crop_window"},
                       "the crop window selects no pixels of the " + std::to_string(settings.width) + "x" +
                           std::to_string(settings.height) + " image");
    options.crop = pixels;
    return options;
  }
  if (const std::optional<PixelBounds> crop = s.job.crop ? s.job.crop : settings.crop) {
    if (crop->x1 > settings.width || crop->y1 > settings.height)
      throw InputError({s.job.crop ? "" : s.scene_path.string(), 0, s.job.crop ? "--crop" : "/film/crop"},
                       "the crop window reaches outside the " + std::to_string(settings.width) + "x" +
                           std::to_string(settings.height) + " image");
    options.crop = *crop;
  }
  return options;
}

// The film's response, its errors named at --film or the scene's /film/response.
SpectralResponse film_response(RenderJobState& s) {
  const RenderSettings& settings = s.loaded.scene->settings;
  try {
    // Rgb transport's lanes are linear sRGB, not wavelengths: its film converts them with the sRGB matrix.
    if (settings.integrator.wavelengths == WavelengthMode::rgb) {
      if (settings.film_response != "xyz") throw InputError({}, "rgb transport renders to an XYZ film only");
      return SpectralResponse::rgb_transport(s.library);
    }
    // A colour-corrected camera film ("camera-xyz:") balances its white in its fitted matrix.
    const WhiteBalanceSettings& white_balance = settings.camera_exposure.white_balance;
    const SpectrumPtr white = white_balance_illuminant(white_balance, s.library);
    return SpectralResponse::from_spec(s.library, settings.film_response, white.get(),
                                       white ? white_balance.describe() : "D65");
  } catch (const InputError& e) {
    throw InputError({"", 0, s.job.film ? "--film" : s.scene_path.string() + ": /film/response"}, e.explanation());
  }
}

// What a partial written after samples [requested.begin, reached) records for a merge or --resume.
PartialRecord job_partial_record(const RenderJobState& s, int reached) {
  const RenderSettings& settings = s.loaded.scene->settings;
  PartialRecord record;
  record.scene_hash = s.loaded.hash;
  record.seed = settings.seed;
  if (reached > s.requested.begin) record.samples = {SampleRange{s.requested.begin, reached}};
  record.requested = s.requested;
  record.total_spp = s.total_spp;
  // A render that ended on its time budget is complete at the samples it reached: --resume has nothing left to
  // do and a merge takes it whole. Stopped earlier (Ctrl-C, a checkpoint), it still asks for the rest of its budget.
  if (s.budget_spent) record.requested.end = record.total_spp = reached;
  record.film_spec = settings.integrator.wavelengths == WavelengthMode::rgb ? "rgb-transport" : settings.film_response;
  record.output_transform = s.output_transform;
  RenderJob recorded = s.job;
  if (!s.time_limit_s) recorded.samples = s.requested;  // a time budget renders from 0; --samples is refused
  recorded.samples_per_pixel = record.total_spp;
  recorded.seed = settings.seed;
  record.job = render_job_json(recorded);
  return record;
}

// The EXR's options after samples [requested.begin, reached) (a checkpoint, or the final image): its metadata and,
// for a partial, its record.
ExrOptions job_exr_options(const RenderJobState& s, int reached, bool interrupted) {
  const Scene& scene = *s.loaded.scene;
  const RenderSettings& settings = scene.settings;
  ExrOptions exr;
  exr.pixel_type = s.job.half_exr ? ExrPixelType::half : ExrPixelType::float32;
  exr.metadata.samples_per_pixel = reached - s.requested.begin;
  exr.metadata.seed = settings.seed;
  exr.metadata.render_time_s =
      s.previous_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - s.render_start).count();
  exr.metadata.interrupted = interrupted;
  exr.metadata.scene = s.scene_path.string();
  exr.metadata.extra["degenerateTrianglesRemoved"] = std::to_string(scene.degenerate_triangles_removed);
  exr.metadata.extra["wavelengths"] = wavelength_mode_name(settings.integrator.wavelengths);
  exr.metadata.extra["wavelengthDensity"] = scene.wavelength_density ? "lights" : "visible";
  exr.metadata.extra["sampler"] = sampler_kind_name(settings.sampler);
  exr.metadata.extra["lightSampler"] = light_sampler_kind_name(settings.light_sampler);
  exr.metadata.extra["guiding"] =
      !settings.integrator.guiding ? "off" : settings.integrator.guiding_mixture ? "mixture" : "on";
  // `rimu display` meters the image again as the render did (render/output/exr_display_source.h).
  if (s.metered_display) exr.metadata.extra["displayMetered"] = "yes";
  for (const auto& [key, value] : exposure_metadata(settings.camera_exposure, s.output_transform))
    exr.metadata.extra[key] = value;
  exr.metadata.camera = settings.camera_exposure.exposure;
  exr.metadata.finished_at = std::time(nullptr);
  // A camera-xyz film balanced its white in its fitted matrix: no matrix a display could undo (rimu display refuses
  // --white-balance on it).
  if (s.film->response().white_balance_in_curves()) exr.metadata.extra["whiteBalanceInFilmResponse"] = "yes";
  if (s.colour_fit) {
    // The written R, G, B are M_wb · raw (times the exposure): undo the white balance to reach the fit's raw input.
    exr.metadata.camera_to_xyz = s.colour_fit->camera_to_xyz * s.output_transform.channel_matrix.inverse();
    exr.metadata.camera_to_xyz_mean_delta_e2000 = s.colour_fit->mean_delta_e2000;
  }
  if (s.partial_output) exr.partial = job_partial_record(s, reached);
  if (s.adaptive) {
    // Per pixel: the samples it took and its relative standard error (render/film/adaptive_sampling.h).
    exr.metadata.extra["noiseThreshold"] = std::to_string(s.adaptive->settings().noise_threshold);
    std::vector<float> spp, error;
    const PixelBounds& b = s.film->pixel_bounds();
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x) {
        spp.push_back(float(s.adaptive->samples(x, y)));
        error.push_back(s.adaptive->relative_error(x, y));
      }
    exr.extra_channels = {{"spp", std::move(spp)}, {"relativeError", std::move(error)}};
  }
  if (s.features && s.aovs.any()) {
    for (auto& layer : aov_channels(*s.features, *s.film, s.aovs)) exr.extra_channels.push_back(std::move(layer));
    exr.metadata.extra["aov"] = aov_list_text(s.aovs);
  }
  return exr;
}

// What the final display image and the previews show: the same policy, so a preview of the same samples is the
// same image.
DisplayImagePolicy display_policy(RenderJobState& s) {
  DisplayImagePolicy policy;
  policy.camera_fit = s.colour_fit;
  policy.white_balanced = s.loaded.scene->settings.camera_exposure.white_balance.kind != WhiteBalanceSettings::Kind::none;
  policy.metered = s.metered_display;
  policy.quiet = s.job.quiet;
  policy.nits_per_unit_y =
      (s.colour_fit ? SpectralResponse::cie_xyz(s.library) : s.film->response()).luminance_nits_per_unit_y();
  return policy;
}

// --preview: the display image of the film as it is (written atomically, so a viewer never reads half a file).
// Its notes and warnings would repeat every interval: the final --png's are the ones logged.
void write_preview(RenderJobState& s) {
  std::ostringstream unlogged;
  if (s.job.preview_output)
    write_policy_display_image(*s.job.preview_output, *s.film, s.display, display_policy(s), unlogged);
  if (s.job.preview_error_output && s.adaptive)
    write_error_heat_map(*s.job.preview_error_output, *s.adaptive, s.film->pixel_bounds());
  s.last_preview = std::chrono::steady_clock::now();
}

// --samples with a time budget (the scene's is checked once it is read) or with adaptive sampling, whose half
// buffers live only in this process: refused before anything is read.
[[noreturn]] void refuse_time_budget_with_samples(const std::string& budget) {
  throw InputError({"", 0, "--samples"},
                   "a render to a time budget (" + budget + ") renders whole passes from sample 0 until the budget "
                   "is spent, so it has no fixed sample range to split: give --spp with --samples for a partial "
                   "render, or drop --samples");
}

void check_adaptive_sampling_options(const RenderJob& job) {
  if (job.preview_error_output && !job.noise_threshold)
    throw InputError({job.preview_error_output->string(), 0, "--preview-error"},
                     "a heat map of the remaining error needs the error estimate of adaptive sampling: give "
                     "--noise-threshold");
  if (job.noise_threshold && (job.samples || job.checkpoint_interval_s))
    throw InputError({"", 0, job.samples ? "--samples" : "--checkpoint"},
                     "--noise-threshold stops each pixel on its own noise estimate, which lives in the render's "
                     "memory, not in a partial: it cannot be split into sample ranges (--samples) for `rimu merge` "
                     "or checkpointed and resumed (--checkpoint, --resume); render it in one process");
}

// --aov and --denoise: the feature buffers live in the render's memory, not in a partial.
void check_feature_options(const RenderJob& job) {
  if (!(job.aovs.any() || job.denoise)) return;
  const char* what = job.denoise ? "--denoise" : "--aov";
  if (job.samples || job.checkpoint_interval_s || job.resume)
    throw InputError({"", 0, job.samples ? "--samples" : job.checkpoint_interval_s ? "--checkpoint" : "--resume"},
                     std::string(what) + " needs the render's feature buffers and half buffers, which live in its "
                     "memory, not in a partial: it cannot be split into sample ranges (--samples) for `rimu merge` "
                     "or checkpointed and resumed (--checkpoint, --resume); render it in one process");
}

// A time budget (--time, else the scene's) and the maximum spp it renders to: --spp, else the scene's "spp" when
// the budget is the scene's own, else none (kMaxSamplesPerPixel).
void plan_time_budget(RenderJobState& s) {
  const RenderSettings& settings = s.loaded.scene->settings;
  s.time_limit_s = s.job.time_limit_s ? s.job.time_limit_s : settings.time_limit_s;
  if (!s.time_limit_s) return;
  if (s.job.samples)
    refuse_time_budget_with_samples(s.job.time_limit_s ? "--time" : s.scene_path.string() + ": /integrator/time_limit_s");
  const bool capped = s.job.samples_per_pixel || (!s.job.time_limit_s && settings.samples_per_pixel_given);
  if (!capped) s.total_spp = kMaxSamplesPerPixel;
}

// --noise-threshold: adaptive sampling over the film, the minimum spp from the maximum (or 16 with none, a time
// budget without --spp). Its half buffers live only in this process: no partials.
void plan_adaptive_sampling(RenderJobState& s) {
  if (!s.job.noise_threshold) return;
  check_adaptive_sampling_options(s.job);
  AdaptiveSamplingSettings settings;
  settings.noise_threshold = *s.job.noise_threshold;
  settings.min_spp = adaptive_min_spp(s.total_spp == kMaxSamplesPerPixel ? 0 : s.total_spp);
  settings.max_spp = s.total_spp;
  s.adaptive = std::make_unique<AdaptiveSampling>(*s.film, settings);
}

}  // namespace

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
  if (job.daylit_points) document["integrator"]["daylit_points"] = *job.daylit_points;
  if (job.caustics) document["integrator"]["caustics"] = *job.caustics;
  if (job.method) document["integrator"]["method"] = *job.method;
  if (job.max_sample_value) document["film"]["max_sample_value"] = *job.max_sample_value;
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

RenderJobState::RenderJobState(const RenderJob& job_in, const PartialImage* previous_in,
                               const DisplayOptions& display_in, std::ostream& log_in)
    : job(job_in),
      previous(previous_in),
      log(log_in),
      display(display_in),
      library(SpectralLibrary::at_default_location()),
      scene_path(job.scene ? *job.scene : default_scene_path(library)) {}

DisplayOptions check_job_without_scene(const RenderJob& job) {
  check_render_outputs(job.exr_output, job.png_output);
  if (job.preview_output) check_preview_output(*job.preview_output, job.exr_output, job.png_output);
  if (job.preview_error_output)
    check_preview_error_output(*job.preview_error_output, job.exr_output, job.png_output, job.preview_output);
  if (job.time_limit_s && job.samples) refuse_time_budget_with_samples("--time");
  check_adaptive_sampling_options(job);
  check_feature_options(job);
  DisplayOptions display;
  display.exposure_ev = job.exposure_ev;
  display.view = job.view;
  // The view and the exposure matter only to display images, but the job records them (a resumed render or a
  // merge of its partials may write one later): checked when the job writes a display image or when either was
  // given other than its default. Otherwise OpenColorIO is never loaded (display_module/display_module_api.h).
  const bool writes_display = job.png_output || job.preview_output || job.preview_error_output;
  if (writes_display || job.view != DisplayOptions{}.view || job.exposure_ev != 0.0)
    const DisplayTransform display_check(ResponseKind::cie_xyz, display);  // the view, the exposure, the config
  return display;
}

void read_job_scene(RenderJobState& s) {
  s.loaded = load_job_scene(s.job, s.scene_path, s.library, s.log);
  check_render_outputs_not_inputs(s.job.exr_output, s.job.png_output, s.loaded.files_read, s.job.preview_output,
                                  s.job.preview_error_output);
  check_scene_hash(s);
  for (const std::string& warning : s.loaded.scene->warnings) s.log << "rimu: warning: " << warning << "\n";
  apply_job_options(s.job, s.loaded.scene->settings, s.library);
}

void set_up_film(RenderJobState& s) {
  const RenderJob& job = s.job;
  const RenderSettings& settings = s.loaded.scene->settings;
  const FilmOptions options = film_options(s);
  s.film = std::make_unique<Film>(options, film_response(s), s.loaded.scene->light_groups);
  Film& film = *s.film;
  if (settings.camera_exposure.exposure) {
    try {
      film_exposure_scale(*settings.camera_exposure.exposure, film.response());
    } catch (const InputError& e) {
      throw InputError({"", 0, has_camera_options(job) ? "--iso/--shutter/--f-number/--ev"
                                                       : s.scene_path.string() + ": /camera/exposure"},
                       e.explanation());
    }
  }
  // Exposure and white balance reach the EXR and the PNG through the film's output transform (one place).
  try {
    s.output_transform = film_output_transform(settings.camera_exposure, film.response(), s.library);
  } catch (const InputError& e) {
    throw InputError({"", 0, job.white_balance ? "--white-balance" : s.scene_path.string() + ": /camera/white_balance"},
                     e.explanation());
  }
  film.set_output_transform(s.output_transform);
  film.set_max_sample_value(settings.max_sample_value);
  s.aovs = job.aovs.any() ? job.aovs : settings.aovs;
  if (s.aovs.any() && !job.aovs.any() && (job.samples || job.checkpoint_interval_s || s.previous))
    throw InputError({s.scene_path.string(), 0, "/film/aov"},
                     "feature layers need the render's feature buffers, which live in its memory, not in a partial: "
                     "render the scene in one process (no --samples, --checkpoint or --resume), or remove \"aov\"");
  if (s.aovs.any() || job.denoise) s.features = std::make_unique<FeatureBuffers>(film.pixel_bounds());
  // Metropolis light transport: its chains and its estimate of the image's brightness live in the render's memory.
  if (settings.integrator.metropolis && (job.samples || job.checkpoint_interval_s || s.previous))
    throw InputError({s.scene_path.string(), 0, "/integrator/method"},
                     "Metropolis light transport's Markov chains live in the render's memory, not in a partial: it "
                     "cannot be split into sample ranges (--samples) for `rimu merge` or checkpointed and resumed "
                     "(--checkpoint, --resume); render it in one process, or with another method (--method)");
  s.filter = make_filter(settings.filter);
  if (film.response().kind() == ResponseKind::camera_rgb) s.colour_fit = fit_camera_to_xyz(film.response(), s.library);
  s.metered_display = !settings.camera_exposure.exposure && s.loaded.scene->photometric_lights;
}

void plan_samples(RenderJobState& s) {
  s.total_spp = s.loaded.scene->settings.samples_per_pixel;
  plan_time_budget(s);
  plan_adaptive_sampling(s);
  s.requested = s.job.samples.value_or(SampleRange{0, s.total_spp});
  if (s.requested.end > s.total_spp)
    throw InputError({"", 0, "--samples"}, "--samples " + s.requested.text() + " reaches beyond the render's " +
                                               std::to_string(s.total_spp) +
                                               " samples per pixel (the scene's samples_per_pixel, or --spp)");
  s.partial_output = s.job.samples || s.job.checkpoint_interval_s || s.previous;
  s.first_sample = s.requested.begin;
  if (s.previous) {
    const ResumePoint resume = resume_on_film(*s.previous, *s.film);
    s.first_sample = resume.first_sample;
    s.previous_seconds = resume.render_time_s;
  }
}

void render_samples(RenderJobState& s, InterruptFlag& interrupt) {
  const RenderJob& job = s.job;
  const RenderSettings& settings = s.loaded.scene->settings;
  const uint64_t total = uint64_t(s.film->pixel_bounds().area()) * uint64_t(s.requested.end - s.first_sample);
  ProgressReporter::Options progress_options;
  progress_options.silent = job.quiet;  // --quiet: nothing on stderr but warnings and errors
  if (s.time_limit_s) {
    progress_options.time_budget_s = *s.time_limit_s;
    progress_options.time_spent_s = s.previous_seconds;
  }
  ProgressReporter progress(total, "rendering", progress_options);

  RenderOptions options;
  options.samples_per_pixel = s.requested.end;
  options.first_sample = s.first_sample;
  options.threads = job.threads.value_or(0);
  options.seed = settings.seed;
  options.sampler = settings.sampler;
  options.interrupt = &interrupt;
  options.progress = &progress;
  s.render_start = std::chrono::steady_clock::now();
  s.last_preview = s.render_start;
  auto last_checkpoint = s.render_start;
  const auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  std::optional<TimeBudget> budget;
  if (s.time_limit_s) budget.emplace(*s.time_limit_s, s.previous_seconds);
  options.adaptive = s.adaptive.get();
  options.features = s.features.get();
  if (budget || s.adaptive) {
    options.start_pass = [&](int first, int count) {
      if (s.adaptive && s.adaptive->active_count() == 0) {
        s.converged = true;  // every pixel stopped: the render is complete
        return false;
      }
      // Adaptive: the pass's samples shared among the pixels, and their mean for the budget's prediction.
      const double pass_samples =
          s.adaptive ? double(s.adaptive->plan_pass(count)) / double(s.film->pixel_bounds().area()) : double(count);
      return !budget || budget->allows_pass(seconds_since(s.render_start), pass_samples, first == s.requested.begin);
    };
  }
  options.after_pass = [&](int reached) {
    if (s.adaptive) s.adaptive->after_pass(*s.film, reached);
    if (job.checkpoint_interval_s && reached < s.requested.end &&
        seconds_since(last_checkpoint) >= *job.checkpoint_interval_s) {
      write_exr(job.exr_output, *s.film, job_exr_options(s, reached, false));
      last_checkpoint = std::chrono::steady_clock::now();
      if (!job.quiet) s.log << "\nrimu: checkpoint " << job.exr_output.string() << ": samples " << s.requested.begin
                            << ":" << reached << "\n";
    }
    // The first pass's preview at once (something to look at), then one per interval; the last is written with
    // the outputs.
    if ((job.preview_output || job.preview_error_output) && (reached < s.requested.end || s.adaptive) &&
        (reached == sample_pass_end(s.first_sample) || seconds_since(s.last_preview) >= job.preview_interval_s))
      write_preview(s);
  };
  s.result.statistics = render(*s.loaded.scene, *s.filter, *s.film, options);
  s.budget_spent = budget && budget->spent();
  if (s.budget_spent || s.converged) progress.mark_complete();
  progress.finish();
  s.result.sample_counts = s.film->sample_counts();
  s.reached = s.first_sample + s.result.statistics.samples_per_pixel_done;
  // Adaptive: the schedule's position is no pixel's count; the render reached the most any pixel took.
  if (s.adaptive) s.reached = s.first_sample + s.adaptive->max_samples();
}

void write_job_outputs(RenderJobState& s) {
  const RenderJob& job = s.job;
  ExrOptions exr = job_exr_options(s, s.reached, s.result.statistics.interrupted);
  if (job.denoise) {
    // The denoised film takes the rendered one's place in the EXR's beauty and the display image.
    DenoiseSettings settings;
    settings.threads = job.threads.value_or(0);
    DenoisedFilm denoised = denoise_film(*s.film, *s.features, settings);
    for (auto& layer : denoised.noisy_layer) exr.extra_channels.push_back(std::move(layer));
    exr.metadata.extra["denoised"] =
        "weighted first-order regression on albedo, normal and depth (NFOR, simplified); noisy beauty in the noisy layer";
    if (!job.quiet)
      s.log << "rimu: denoised in " << denoised.seconds << " s ("
            << denoised.seconds / (double(s.film->pixel_bounds().area()) * 1e-6) << " s per megapixel)\n";
    s.film = std::move(denoised.film);
  }
  write_render_exr(job.exr_output, *s.film, exr, s.log);
  if (job.png_output) write_policy_display_image(*job.png_output, *s.film, s.display, display_policy(s), s.log);
  if (job.preview_output || job.preview_error_output) write_preview(s);
}

void log_job_summary(const RenderJobState& s) {
  const RenderJob& job = s.job;
  const RenderStatistics& statistics = s.result.statistics;
  const FilmSampleCounts& c = s.result.sample_counts;
  std::ostringstream summary;
  summary << "rimu: " << s.scene_path.string() << ": " << s.reached - s.requested.begin << " spp";
  if (job.samples || s.previous) summary << " (samples " << s.requested.begin << ":" << s.reached << ")";
  if (s.converged) summary << " (every pixel below the noise threshold)";
  else if (s.budget_spent) summary << " (the time budget of " << *s.time_limit_s << " s was spent)";
  else if (statistics.interrupted && s.time_limit_s)
    summary << " (interrupted before the time budget of " << *s.time_limit_s << " s was spent)";
  else if (statistics.interrupted) summary << " (interrupted; requested " << s.requested.count() << ")";
  summary << " in " << statistics.seconds << " s, "
          << (statistics.seconds > 0 ? double(statistics.camera_samples) / statistics.seconds : 0.0)
          << " samples/s; discarded samples: " << c.nan << " NaN, " << c.infinite << " Inf, " << c.negative
          << " negative";
  if (s.film->max_sample_value())
    summary << "; clamped samples: " << c.clamped << " (max_sample_value " << *s.film->max_sample_value() << ")";
  summary << "\n";
  if (s.adaptive) {
    const PixelBounds& b = s.film->pixel_bounds();
    double samples = 0;
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x) samples += s.adaptive->samples(x, y);
    summary << "rimu: adaptive sampling: " << size_t(b.area()) - s.adaptive->active_count() << " of " << b.area()
            << " pixels stopped below the noise threshold " << s.adaptive->settings().noise_threshold
            << "; mean " << samples / double(b.area()) << " spp\n";
  }
  if (const GuidingStatistics& g = statistics.guiding; g.active)
    summary << "rimu: path guiding: " << g.training_passes << " training passes, largest field " << g.spatial_leaves
            << " spatial leaves, " << g.directional_nodes << " directional nodes (or lobes), "
            << double(g.memory_bytes) / (1024.0 * 1024.0) << " MiB\n";
  if (statistics.metropolis)
    summary << "rimu: Metropolis light transport over "
            << (statistics.bidirectional ? "bidirectional path tracing" : "the path tracer") << "\n";
  else if (s.loaded.scene && s.loaded.scene->settings.integrator.metropolis)
    summary << "rimu: path-traced: Metropolis light transport needs a render without light groups, spectral bins, "
               "feature buffers (--aov, --denoise), adaptive sampling or a sample clamp (--max-sample-value)\n";
  else if (statistics.bidirectional && statistics.vertex_merging)
    summary << "rimu: vertex connection and merging (per sample index " << statistics.merge_light_subpaths
            << " light subpaths, each joined by its pixel's camera sample and merged with by every camera vertex; last "
               "pass "
            << statistics.merge_vertices << " light vertices to merge with, radius " << statistics.merge_radius_m
            << " m; " << double(statistics.merge_memory_bytes) / (1024.0 * 1024.0) << " MiB at most)\n";
  else if (statistics.bidirectional)
    summary << "rimu: bidirectional path tracing (one light subpath per camera sample)\n";
  else if (s.loaded.scene && s.loaded.scene->settings.integrator.bidirectional)
    summary << "rimu: path-traced: bidirectional path tracing needs a pinhole or thin-lens camera, no media and no "
               "adaptive sampling\n";
  if (statistics.caustic_light_tracing)
    summary << "rimu: caustics of lamps and emitting shapes light-traced (one light path per camera sample)\n";
  else if (s.loaded.scene && s.loaded.scene->settings.integrator.caustic_light_tracing)
    summary << "rimu: caustics path-traced: light tracing needs a pinhole or thin-lens camera, no media and no adaptive sampling\n";
  if (!s.film->light_groups().empty()) {
    summary << "rimu: light groups, one EXR layer each (rebalance them with rimu display --group):";
    for (const std::string& group : s.film->light_groups()) summary << " " << group;
    summary << "\n";
  }
  summary << "rimu: wrote " << job.exr_output.string();
  if (job.png_output) summary << " and " << job.png_output->string();
  summary << "\n";
  if (!job.quiet) s.log << summary.str();
}

}  // namespace rimu
