#include "render/render_job.h"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "render/camera_exposure.h"
#include "render/display_output.h"
#include "render/exr_output.h"
#include "render/output_file.h"
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

// --iso, --shutter, --f-number, --ev, --white-balance over the scene camera's exposure and white balance.
void apply_camera_options(const RenderJob& job, CameraExposureSettings& camera, SpectralLibrary& library) {
  if (job.iso || job.shutter_s || job.f_number || job.compensation_ev) {
    PhysicalCameraSettings e = camera.exposure.value_or(PhysicalCameraSettings{});
    if (job.iso) e.iso = *job.iso;
    if (job.shutter_s) e.shutter_s = *job.shutter_s;
    if (job.f_number) e.f_number = *job.f_number;
    if (job.compensation_ev) e.exposure_compensation_ev = *job.compensation_ev;
    if (!(e.iso > 0.0) || !(e.shutter_s > 0.0) || !(e.f_number > 0.0) || !std::isfinite(e.exposure_compensation_ev))
      throw InputError({"", 0, "--iso/--shutter/--f-number/--ev"},
                       "the physical camera needs a positive ISO, shutter time and f-number and a finite --ev");
    camera.exposure = e;
  }
  if (job.white_balance)
    camera.white_balance = parse_white_balance_option(*job.white_balance, library, "--white-balance");
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

RenderJobResult run_render_job(const RenderJob& job, std::ostream& log) {
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const std::filesystem::path scene_path = job.scene ? *job.scene : default_scene_path(library);
  std::unique_ptr<Scene> scene;
  if (job.wavelengths || job.wavelength_density || job.light_sampler) {
    nlohmann::json document = parse_json_file(scene_path);
    if (job.wavelengths) document["integrator"]["wavelengths"] = wavelength_mode_name(*job.wavelengths);
    if (job.wavelength_density)
      document["integrator"]["wavelength_density"] =
          *job.wavelength_density == WavelengthDensityKind::lights ? "lights" : "visible";
    if (job.light_sampler) document["integrator"]["light_sampler"] = light_sampler_kind_name(*job.light_sampler);
    scene = load_scene(document, scene_path.string(), scene_path.parent_path(), library);
  } else {
    scene = load_scene(scene_path, library);
  }

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
  // Check the outputs before spending the render time on an image that cannot be written.
  check_output_path(job.exr_output);
  if (job.png_output) check_output_path(*job.png_output);

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
  write_exr(job.exr_output, film, exr);
  if (job.png_output) {
    DisplayOptions display;
    display.exposure_ev = job.exposure_ev;
    display.view = job.view;
    write_display_png(*job.png_output, film, display);
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
