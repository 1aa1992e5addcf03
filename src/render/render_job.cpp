#include "render/render_job.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <ostream>
#include <sstream>

#include "render/camera_colour_matrix.h"
#include "render/camera_exposure.h"
#include "render/display_image_policy.h"
#include "render/display_output.h"
#include "render/exr_output.h"
#include "render/output_file.h"
#include "render/pbrt/pbrt_to_scene.h"
#include "spectral/error.h"
#include "render/interrupt_flag.h"
#include "render/json_cursor.h"
#include "render/progress_reporter.h"
#include "render/scene.h"

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

nlohmann::json read_pbrt_scene(const std::filesystem::path& path, SpectralLibrary& library, bool strict, std::ostream& log) {
  PbrtImport imported = import_pbrt(path, library, {strict, {}});
  log << describe_ignored(imported.ignored);
  return std::move(imported.document);
}

RenderJobResult run_render_job(const RenderJob& job, std::ostream& log) {
  // Everything that can be checked without the scene is checked first: a typo costs nothing.
  check_outputs(job);
  DisplayOptions display;
  display.exposure_ev = job.exposure_ev;
  display.view = job.view;
  const DisplayTransform display_check(ResponseKind::cie_xyz, display);  // the view, the exposure, the config
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const std::filesystem::path scene_path = job.scene ? *job.scene : default_scene_path(library);
  // pbrt-v4 files are translated into a JSON document first; both then go through the same loader.
  const bool pbrt = is_pbrt_scene_path(scene_path);
  nlohmann::json document = pbrt ? read_pbrt_scene(scene_path, library, job.strict, log) : parse_json_file(scene_path);
  if (job.wavelengths) document["integrator"]["wavelengths"] = wavelength_mode_name(*job.wavelengths);
  if (job.wavelength_density)
    document["integrator"]["wavelength_density"] =
        *job.wavelength_density == WavelengthDensityKind::lights ? "lights" : "visible";
  if (job.light_sampler) document["integrator"]["light_sampler"] = light_sampler_kind_name(*job.light_sampler);
  const std::unique_ptr<Scene> scene = load_scene(document, scene_path.string(), scene_path.parent_path(), library);

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
  if (job.crop) {
    if (job.crop->x1 > settings.width || job.crop->y1 > settings.height)
      throw InputError({"", 0, "--crop"}, "the crop window reaches outside the " + std::to_string(settings.width) + "x" +
                                              std::to_string(settings.height) + " image");
    film_options.crop = *job.crop;
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

  InterruptFlag interrupt;
  const uint64_t total = uint64_t(film.pixel_bounds().area()) * uint64_t(settings.samples_per_pixel);
  ProgressReporter::Options progress_options;
  if (job.quiet) progress_options.terminal = 0;
  ProgressReporter progress(total, "rendering", progress_options);

  RenderOptions options;
  options.samples_per_pixel = settings.samples_per_pixel;
  options.threads = job.threads.value_or(0);
  options.seed = settings.seed;
  options.sampler = settings.sampler;
  options.interrupt = &interrupt;
  options.progress = &progress;
  RenderJobResult result;
  result.statistics = render(*scene, filter, film, options);
  progress.finish();
  result.sample_counts = film.sample_counts();

  ExrOptions exr;
  exr.pixel_type = job.float_exr ? ExrPixelType::float32 : ExrPixelType::half;
  exr.metadata.samples_per_pixel = result.statistics.samples_per_pixel_done;
  exr.metadata.seed = settings.seed;
  exr.metadata.render_time_s = result.statistics.seconds;
  exr.metadata.interrupted = result.statistics.interrupted;
  exr.metadata.scene = scene_path.string();
  exr.metadata.extra["degenerateTrianglesRemoved"] = std::to_string(scene->degenerate_triangles_removed);
  exr.metadata.extra["wavelengths"] = wavelength_mode_name(settings.integrator.wavelengths);
  exr.metadata.extra["wavelengthDensity"] = scene->wavelength_density ? "lights" : "visible";
  exr.metadata.extra["sampler"] = sampler_kind_name(settings.sampler);
  exr.metadata.extra["lightSampler"] = light_sampler_kind_name(settings.light_sampler);
  for (const auto& [key, value] : exposure_metadata(settings.camera_exposure, output_transform))
    exr.metadata.extra[key] = value;
  exr.metadata.camera = settings.camera_exposure.exposure;
  exr.metadata.finished_at = std::time(nullptr);
  if (colour_fit) {
    // The written R, G, B are M_wb · raw (times the exposure): undo the white balance to reach the fit's raw input.
    exr.metadata.camera_to_xyz = colour_fit->camera_to_xyz * output_transform.channel_matrix.inverse();
    exr.metadata.camera_to_xyz_mean_delta_e2000 = colour_fit->mean_delta_e2000;
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
    policy.nits_per_unit_y =
        (colour_fit ? SpectralResponse::cie_xyz(library) : film.response()).luminance_nits_per_unit_y();
    write_policy_display_image(*job.png_output, film, display, policy, log);
  }

  const FilmSampleCounts& c = result.sample_counts;
  std::ostringstream summary;
  summary << "rimu: " << scene_path.string() << ": " << result.statistics.samples_per_pixel_done << " spp";
  if (result.statistics.interrupted) summary << " (interrupted; requested " << settings.samples_per_pixel << ")";
  summary << " in " << result.statistics.seconds << " s, "
          << (result.statistics.seconds > 0 ? double(result.statistics.camera_samples) / result.statistics.seconds : 0.0)
          << " samples/s; discarded samples: " << c.nan << " NaN, " << c.infinite << " Inf, " << c.negative
          << " negative\n";
  summary << "rimu: wrote " << job.exr_output.string();
  if (job.png_output) summary << " and " << job.png_output->string();
  summary << "\n";
  log << summary.str();
  return result;
}

}  // namespace rimu
