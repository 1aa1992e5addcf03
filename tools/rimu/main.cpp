// rimu: renders a scene (by default the embedded spectral Cornell box) to OpenEXR, and optionally a PNG preview.
//
// Exit codes (common/tool_main.h): 0 ok (also after Ctrl-C: the image reached so far is written), 1 bad input,
// 2 runtime failure.
#include <iostream>

#include "common/tool_main.h"

#include "render/camera/camera_exposure.h"
#include "render/scene/scene_sensors.h"
#include "render/installation_check.h"
#include "render/render_job.h"
#include "render/film/render_size.h"
#include "display_command.h"
#include "denoise_command.h"
#include "merge_command.h"
#include "spectral/error.h"

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "merge") return run_merge_command(argc - 1, argv + 1);
  if (argc > 1 && std::string(argv[1]) == "display") return run_display_command(argc - 1, argv + 1);
  if (argc > 1 && std::string(argv[1]) == "denoise") return run_denoise_command(argc - 1, argv + 1);
  CLI::App app{
      "rimu: spectral hero-wavelength path tracer.\n"
      "Renders SCENE (a JSON file, see docs/scene-format.md; default: the measured Cornell box) to an OpenEXR image\n"
      "of CIE XYZ (or camera RGB) and optionally a PNG for display. Ctrl-C stops early and still writes the image.\n"
      "Example: rimu -o box.exr --png box.png --spp 64\n"
      "Partial renders, checkpoints and farms: docs/farm.md; `rimu merge --help` merges partial renders;\n"
      "`rimu display --help` re-exposes a rendered EXR without rendering; `rimu denoise --help` denoises one."};
  rimu::RenderJob job;
  std::string scene, output = "rimu.exr", png, film, resolution, crop, sampler, wavelengths, wavelength_density,
      light_sampler, guiding, daylit_points, caustics, method;
  app.add_option("scene", scene, "scene file (.json, or a pbrt-v4 .pbrt: see docs/pbrt-import.md); omit for the embedded Cornell box");
  app.add_option("-o,--output", output, "scene-referred OpenEXR output, a name ending in .exr (default rimu.exr)");
  app.add_option("--png", png, "also write a display image (sRGB through OpenColorIO): 8-bit PNG, or JPEG or TIFF "
                               "by the extension (.png, .jpg, .tif); a photometric scene without a camera exposure "
                               "is metered to 18 % grey");
  app.add_option("--spp", job.samples_per_pixel, "samples per pixel (overrides the scene); with --time, the maximum")->check(CLI::Range(1, rimu::kMaxSamplesPerPixel));
  app.add_option("--threads", job.threads, "worker threads (default: every core)")->check(CLI::Range(1, rimu::kMaxRenderThreads));
  app.add_option("--seed", job.seed, "random seed (the image is identical for the same seed and spp)");
  app.add_option("--sampler", sampler, "sobol (Owen-scrambled Sobol', the default) or independent (overrides the scene)")
      ->check(CLI::IsMember({"sobol", "independent"}));
  app.add_option("--wavelengths", wavelengths,
                 "hero (4 lanes with spectral MIS, the default), single, independent (4 lanes, no MIS) or rgb "
                 "(RGB transport, a baseline only; see docs/transport.md) (overrides the scene)")
      ->check(CLI::IsMember({"hero", "single", "independent", "rgb"}));
  app.add_option("--wavelength-density", wavelength_density,
                 "visible (follows the colour-matching functions, the default) or lights (follows the scene's "
                 "emission too: less colour noise under line spectra such as F11; see docs/sampling.md) "
                 "(overrides the scene)")
      ->check(CLI::IsMember({"visible", "lights"}));
  app.add_option("--light-sampler", light_sampler,
                 "bvh (chooses lights by their estimated contribution at each point, the default), bvh-spectral "
                 "(the same, at the path's four wavelengths; see docs/sampling.md), power (by radiant power only) "
                 "or uniform (see docs/transport.md) (overrides the scene)")
      ->check(CLI::IsMember({"bvh", "bvh-spectral", "power", "uniform"}));
  app.add_option("--guiding", guiding,
                 "on: learn where light comes from while rendering and sample directions from it (path guiding; "
                 "somewhat less noise per sample on interiors lit indirectly, but each sample costs more: measured in "
                 "docs/benchmarks.md), mixture: the same with a parallax-aware "
                 "mixture of lobes per region instead of a quadtree, off: the default (overrides the scene)")
      ->check(CLI::IsMember({"on", "off", "mixture"}));
  app.add_option("--daylit-points", daylit_points,
                 "on: each path also traces one ray of daylight (a sun, a sky with portals) into the scene and "
                 "connects to the point it lights (daylit interiors; see docs/transport.md), off, or auto: on where "
                 "daylight enters through portals, the default (overrides the scene)")
      ->check(CLI::IsMember({"on", "off", "auto"}));
  app.add_option("--caustics", caustics,
                 "light_tracing: each sample also traces one light path from a lamp through glass, water and mirrors "
                 "to the first diffuse surface, seen by the camera (caustics of spots and small lamps; see "
                 "docs/transport.md), path_tracing: the default (overrides the scene)")
      ->check(CLI::IsMember({"path_tracing", "light_tracing"}));
  app.add_option("--method", method,
                 "bidirectional: each sample also traces a light subpath and joins every vertex of it to every vertex "
                 "of the camera's, weighted by MIS (light that arrives by way of lit surfaces near the lights: lamps "
                 "under shades, caustics seen in mirrors; see docs/transport.md), vcm: bidirectional plus vertex "
                 "merging (photon mapping weighted by the same MIS: a pool floor seen and lit through water; "
                 "consistent, not unbiased), metropolis: Metropolis light transport over the path tracer (paths found once are "
                 "explored by small changes: light that arrives through a gap; consistent, see docs/transport.md), "
                 "path_tracing: the default (overrides the scene)")
      ->check(CLI::IsMember({"path_tracing", "bidirectional", "vcm", "metropolis"}));
  app.add_option("--film", film, "xyz (CIE 1931 2°), xyz10 (CIE 1964 10°), camera:<name> (measured sensor, raw), "
                                 "camera-xyz:<name> (the sensor through its fitted matrix to XYZ), "
                                 "spectral:<bins> (adds a spectral framebuffer)");
  std::string max_sample_value;
  app.add_option("--max-sample-value", max_sample_value,
                 "clamp: scale each camera sample down so that its largest channel (in the written image's units, "
                 "after exposure) is at most this; removes fireflies at the cost of a darker, biased image (see "
                 "docs/rendering.md, \"Sample clamp\") (overrides the scene's film \"max_sample_value\")");
  app.add_option("--resolution", resolution, "WIDTHxHEIGHT (overrides the scene)");
  app.add_option("--crop", crop, "x0,y0,x1,y1: render only this window (pixels, end exclusive)");
  CLI::Option* half = app.add_flag(
      "--half", job.half_exr,
      "write half-float EXR channels (half the size of the default 32-bit floats, but 0.05 % precision only "
      "between 6.1e-5 and 65504 in film units: a scene lit in lux without an exposure falls below; rimu warns)");
  bool float_alias = false;  // 32-bit floats are the default; the flag stays for command lines written before
  app.add_flag("--float", float_alias, "32-bit float EXR channels: the default (kept for old command lines)")
      ->excludes(half);
  app.add_option("--exposure", job.exposure_ev, "exposure of the display image in stops (EV), -60 to 60");
  app.add_option("--view", job.view, "OpenColorIO view of the PNG: Standard, \"ACES 1.0 SDR\" or Raw");
  app.add_flag("-q,--quiet", job.quiet, "print nothing on stderr but warnings and errors (no progress, no summary)");
  app.add_flag("--strict", job.strict, "pbrt-v4 scenes: anything Rimu does not support is an error, not a report");
  std::string shutter;
  app.add_option("--iso", job.iso, "physical camera: ISO speed (turns the physical camera on; see docs/light-units.md)");
  app.add_option("--shutter", shutter, "physical camera: shutter time in seconds, e.g. 0.01 or 1/100");
  app.add_option("--f-number", job.f_number, "physical camera: f-number, e.g. 16");
  app.add_option("--ev", job.compensation_ev, "physical camera: exposure compensation in stops");
  app.add_option("--white-balance", job.white_balance, "none, a temperature (2700 or 2700K) or an illuminant (A, D50...)");

  std::string time_limit, preview, preview_interval;
  app.add_option("--time", time_limit, "render whole passes until this much render time is spent (90s, 1.5m, 1h, "
                                       "or seconds); --spp is then the maximum, without it there is none");
  app.add_option("--preview", preview, "rewrite this display image (PNG, JPEG or TIFF, as --png) while rendering, "
                                       "so a viewer that reloads it shows the render refining");
  app.add_option("--preview-interval", preview_interval, "the preview after a pass once this long has passed since "
                                                         "the last (default 5s), and at the end");
  app.add_option("--noise-threshold", job.noise_threshold,
                 "adaptive sampling: a pixel stops taking samples once the relative standard error of its luminance "
                 "is below this (0.01: 1 %); --spp is the maximum; the EXR gets 'spp' and 'relativeError' channels")
      ->check(CLI::Range(1e-6, 10.0));
  std::string preview_error;
  app.add_option("--preview-error", preview_error,
                 "with --noise-threshold: rewrite this PNG with a false-colour heat map of each pixel's remaining "
                 "error (%) with every preview and at the end");
  std::string aov;
  app.add_option("--aov", aov, "write feature layers into the EXR: a comma-separated list of albedo, normal, depth, "
                               "variance, halves, or all (what `rimu denoise` needs; docs/rendering.md)");
  app.add_flag("--denoise", job.denoise, "denoise the image (EXR beauty and --png; the noisy beauty is kept as the "
                                         "EXR layer 'noisy'); costs a feature ray per sample and the denoiser");
  std::string sensors_out;
  app.add_flag("--sensors-only", job.sensors_only,
               "measure the scene's \"sensors\" (lux grids and meters, docs/scene-format.md) without rendering the image");
  app.add_option("--sensors-out", sensors_out, "base name of the sensors' BASE.csv and BASE.json (default: beside the "
                                               "EXR, render.exr -> render.sensors.csv)");
  app.add_option("--sensor-samples", job.sensor_samples, "samples per sensor point (overrides the scene's sensors.samples)")
      ->check(CLI::Range(1, rimu::kMaxSensorSamples));

  std::string samples, checkpoint, resume, expect_hash;
  bool print_hash = false;
  app.add_option("--samples", samples, "render only sample indices BEGIN:END of every pixel (END exclusive), a "
                                       "partial for `rimu merge`; --spp is then the whole render's spp");
  app.add_option("--checkpoint", checkpoint, "write -o as a resumable partial every interval (30s, 10m, 1h), and on "
                                             "Ctrl-C or SIGTERM");
  app.add_option("--resume", resume, "continue the partial or checkpoint FILE.exr to the samples it was asked for "
                                     "(its recorded options; -o defaults to FILE.exr)");
  app.add_option("--frame", job.frame, "frame number substituted for ${frame} in the scene and output names");
  app.add_option("--expect-scene-hash", expect_hash, "refuse to render unless the scene hashes to this (farm tasks)");
  app.add_flag("--print-scene-hash", print_hash,
               "print the scene hash (scene file, the files it names, image options) and exit");
  bool check_install = false;
  app.add_flag("--check-install", check_install,
               "load everything a render loads only when a scene needs it (the data folder, the OpenImageIO, "
               "FreeImage and OpenColorIO modules, the display config), print where each was found, and exit "
               "(status 2 if any is missing; for farm nodes: docs/farm.md)");

  return rimu::run_tool("rimu", app, argc, argv, [&] {
    if (check_install) {
      int missing = 0;
      for (const rimu::InstallationItem& item : rimu::check_installation()) {
        std::cout << (item.ok ? "ok       " : "MISSING  ") << item.name << ": " << item.detail << "\n";
        missing += item.ok ? 0 : 1;
      }
      if (missing > 0)
        throw rimu::RenderError(std::to_string(missing) + " part(s) of the installation could not be loaded (above)");
      return;
    }
    if (!scene.empty()) job.scene = scene;
    job.exr_output = output;
    if (!png.empty()) job.png_output = png;
    if (!sensors_out.empty()) job.sensors_output = sensors_out;
    if (!aov.empty()) job.aovs = rimu::parse_aov_list(aov, "--aov");
    if (!film.empty()) job.film = film;
    if (!sampler.empty()) job.sampler = rimu::parse_sampler_kind(sampler);
    if (!wavelengths.empty()) job.wavelengths = rimu::parse_wavelength_mode(wavelengths);
    if (!wavelength_density.empty())
      job.wavelength_density = wavelength_density == "lights" ? rimu::WavelengthDensityKind::lights
                                                              : rimu::WavelengthDensityKind::visible;
    if (!light_sampler.empty()) job.light_sampler = rimu::parse_light_sampler_kind(light_sampler);
    if (!guiding.empty()) job.guiding = guiding;
    if (!daylit_points.empty()) job.daylit_points = daylit_points;
    if (!caustics.empty()) job.caustics = caustics;
    if (!method.empty()) job.method = method;
    if (!max_sample_value.empty())
      job.max_sample_value = rimu::parse_max_sample_value(max_sample_value, "--max-sample-value");
    if (!resolution.empty()) {
      const auto [w, h] = rimu::parse_resolution(resolution, "--resolution");
      job.width = w;
      job.height = h;
    }
    if (!crop.empty()) job.crop = rimu::parse_crop(crop, "--crop");
    if (!shutter.empty()) job.shutter_s = rimu::parse_shutter_time_s(shutter, "--shutter");
    if (!samples.empty()) job.samples = rimu::parse_sample_range(samples, "--samples");
    if (!time_limit.empty()) job.time_limit_s = rimu::parse_duration_s(time_limit, "--time");
    if (!preview.empty()) job.preview_output = preview;
    if (!preview_error.empty()) job.preview_error_output = preview_error;
    if (!preview_interval.empty()) {
      if (preview.empty()) throw rimu::InputError({"", 0, "--preview-interval"}, "needs --preview FILE to write");
      job.preview_interval_s = rimu::parse_duration_s(preview_interval, "--preview-interval");
    }
    if (!checkpoint.empty()) job.checkpoint_interval_s = rimu::parse_duration_s(checkpoint, "--checkpoint");
    if (!resume.empty()) {
      // The file records its job (scene, spp, samples, film, every image option): anything else given with
      // --resume would be silently ignored, so it is refused. Only how to run and where to write may change.
      std::string also;
      for (const CLI::Option* option : app.get_options())
        if (option->count() > 0 && !option->check_name("--resume") && !option->check_name("--threads") &&
            !option->check_name("--quiet") && !option->check_name("--output") && !option->check_name("--checkpoint") &&
            !option->check_name("--preview") && !option->check_name("--preview-interval"))
          also += std::string(also.empty() ? "" : ", ") +
                  (option->check_name("scene") ? "the scene '" + scene + "'" : option->get_name());
      if (!also.empty())
        throw rimu::InputError({"", 0, "--resume"},
                               "continues the job recorded in " + resume + " (its scene, --spp, --samples and image "
                               "options, a time budget) and takes only -o, --threads, --checkpoint, --preview, --preview-interval "
                               "and -q; also given: " + also +
                               ". To render with other options, start a new render");
      job.resume = resume;
      if (app.get_option("-o")->count() == 0) job.exr_output = resume;
    }
    if (!expect_hash.empty()) job.expected_scene_hash = expect_hash;
    if (print_hash) {
      std::cout << rimu::scene_hash(job) << "\n";
      return;
    }
    rimu::run_render_job(job, std::cerr);
  });
}
