// The path tracer's benchmark (issue 4) and its throughput ceiling (issue 7): renders a scene (the default
// Cornell box unless told otherwise) at a ladder of sample counts and prints, per thread count, a markdown table of
// wall time, camera samples/s, rays/s (intersection + occlusion), peak resident memory, and the rays/s of the very
// same rays traced through Embree alone. A plain main(): the figures are whole renders, not Google Benchmark loops.
//
//   build/bin/rimu-render-bench [--scene s.json] [--resolution WxH] [--spp 1,4,16,64] [--threads 1,2]
//                               [--seed S] [--sampler independent|sobol] [--record-max-spp N]
//
// Each row renders three times with the same seed:
//  1. plainly, timed: wall seconds, samples/s and peak memory come from this run alone;
//  2. through RecordingRayQueries (render/reports/ray_recorder.h), which counts every query and records it (rows with
//     spp ≤ --record-max-spp). The render is deterministic, so this run issues exactly the rays of run 1; its
//     image must be bit-identical to run 1's (checked: the decorator must not change the result);
//  3. the recorded rays replayed through EmbreeScene::intersect/occluded alone with the same thread count, whose
//     answers must all match the recorded ones (checked: the replay traces the same rays).
// renderer rays/s = rays / (1)'s seconds; ceiling = rays / (3)'s seconds; their ratio is therefore the share of
// the render's wall time that ray queries alone would take. Exit code 2 if a check fails, 1 on bad options.
#include <embree3/rtcore.h>
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.h"
#include "render/film/film.h"
#include "render/film/pixel_filter.h"
#include "render/reports/ray_recorder.h"
#include "render/render_job.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "spectral/error.h"
#include "transport/sampling/sampler.h"
#include "transport/integrators/volumetric_path_integrator.h"

using namespace rimu;

namespace {

struct Options {
  std::optional<std::filesystem::path> scene;
  std::optional<std::pair<int, int>> resolution;
  std::vector<int> spp = {1, 4, 16, 64};
  std::vector<int> threads;  // empty: 1 and every core
  std::optional<uint64_t> seed;
  std::optional<SamplerKind> sampler;
  int record_max_spp = 64;
};

Options parse_options(int argc, char** argv) {
  Options o;
  CLI::App app{"Renders a scene at a ladder of sample counts and thread counts; reports wall time, samples/s, rays/s,\n"
               "peak memory and Embree's own rays/s for the same rays.", "rimu-render-bench"};
  std::string scene, resolution, sampler;
  std::optional<uint64_t> seed;
  app.add_option("--scene", scene, "scene file (default: the embedded Cornell box)");
  app.add_option("--resolution", resolution, "WxH (default: the scene's)");
  app.add_option("--spp", o.spp, "samples per pixel, comma-separated")->delimiter(',')->check(CLI::Range(1, 1 << 20));
  app.add_option("--threads", o.threads, "thread counts, comma-separated (default: 1 and every core)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1 << 20));
  app.add_option("--seed", seed, "the sampler's seed (default: the scene's)");
  app.add_option("--sampler", sampler, "independent or sobol (default: the scene's)")
      ->check(CLI::IsMember({"independent", "sobol"}));
  app.add_option("--record-max-spp", o.record_max_spp,
                 "rays are recorded and replayed through Embree alone for rows with spp <= N (36 bytes/ray)")
      ->check(CLI::Range(1, 1 << 20));
  bench::parse_command_line(app, argc, argv);
  if (!scene.empty()) o.scene = scene;
  if (!resolution.empty()) o.resolution = parse_resolution(resolution, "--resolution");
  if (!sampler.empty()) o.sampler = parse_sampler_kind(sampler);
  o.seed = seed;
  return o;
}

// --- the machine --------------------------------------------------------------------------------------------

// The vector extensions Embree can choose from at run time (it picks the widest the CPU has).
std::string vector_isas() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("flags", 0) != 0) continue;
    line += ' ';
    std::string found;
    for (const char* isa : {"sse4_2", "avx", "avx2", "avx512f"}) {
      std::string word = " ";
      word += isa;
      if (line.find(word + ' ') != std::string::npos) found += word;
    }
    return found.empty() ? " (none of sse4_2 avx avx2 avx512f)" : found;
  }
  return " (unknown)";
}

// Peak resident memory. Linux resets VmHWM to the current RSS when "5" is written to /proc/self/clear_refs
// (proc(5)), which lets each row report its own peak; without that, the peak is the process's since it started.
bool reset_peak_memory() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return bool(out);
}

double peak_memory_mib() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // the kernel writes kB
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// --- rendering ----------------------------------------------------------------------------------------------

std::unique_ptr<Film> make_film(SpectralLibrary& library, const RenderSettings& settings) {
  return std::make_unique<Film>(FilmOptions{settings.width, settings.height, std::nullopt, settings.spectral_bins},
                                SpectralResponse::from_spec(library, settings.film_response));
}

// Bit-identical sums (==, not a tolerance): the decorator forwards the very answers of the geometry it wraps.
bool same_image(const Film& a, const Film& b) {
  const PixelBounds& bounds = a.pixel_bounds();
  for (int y = bounds.y0; y < bounds.y1; ++y)
    for (int x = bounds.x0; x < bounds.x1; ++x)
      if (a.pixel_value(x, y) != b.pixel_value(x, y) || a.weight_sum(x, y) != b.weight_sum(x, y)) return false;
  const FilmSampleCounts ca = a.sample_counts(), cb = b.sample_counts();
  return ca.accepted == cb.accepted && ca.nan == cb.nan && ca.infinite == cb.infinite && ca.negative == cb.negative;
}

struct Row {
  int spp = 0;
  RenderStatistics plain;
  double peak_mib = 0;
  RayCounts rays;
  double decorated_s = 0;
  std::optional<ReplayResult> replay;
};

// Runs one row (see the file comment); returns false if a check failed (after printing why).
bool run_row(SpectralLibrary& library, const Scene& scene, const PixelFilter& filter, int spp, int threads,
             uint64_t seed, bool record, Row& row) {
  RenderOptions options;
  options.samples_per_pixel = spp;
  options.threads = threads;
  options.seed = seed;
  options.sampler = scene.settings.sampler;
  row.spp = spp;

  auto plain_film = make_film(library, scene.settings);
  reset_peak_memory();
  row.plain = render(scene, filter, *plain_film, options);
  row.peak_mib = peak_memory_mib();

  RecordingRayQueries recorder(scene.geometry,
                               record ? RecordingRayQueries::Mode::record : RecordingRayQueries::Mode::count);
  TransportScene view = scene.transport_view();
  view.geometry = &recorder;
  const Camera camera(scene.camera, scene.settings.width, scene.settings.height);
  auto counted_film = make_film(library, scene.settings);
  if (scene.has_media()) {  // the same dispatch as render(const Scene&, ...): media take the volumetric integrator
    VolumetricIntegratorSettings settings;
    settings.path = scene.settings.integrator;
    settings.distance = scene.settings.distance_sampling;
    const VolumetricScene volumetric{view, &scene.media, &scene.medium_boundaries, scene.camera_medium};
    row.decorated_s = render(volumetric, settings, camera, filter, *counted_film, options).seconds;
  } else {
    row.decorated_s = render(view, scene.settings.integrator, camera, filter, *counted_film, options).seconds;
  }
  row.rays = recorder.counts();
  if (!same_image(*plain_film, *counted_film)) {
    std::fprintf(stderr, "FAILED: at %d spp the render through RecordingRayQueries differs from the plain render\n", spp);
    return false;
  }
  if (!record) return true;

  const std::vector<std::vector<RecordedRay>> recording = recorder.take_recording();
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  row.replay = replay_rays(scene.geometry, recording);
  if (row.replay->rays != row.rays.total() || row.replay->mismatches != 0) {
    std::fprintf(stderr, "FAILED: at %d spp the replay traced %llu rays (%llu recorded) with %llu different answers\n",
                 spp, (unsigned long long)row.replay->rays, (unsigned long long)row.rays.total(),
                 (unsigned long long)row.replay->mismatches);
    return false;
  }
  return true;
}

void print_row(const Row& r) {
  const double samples = double(r.plain.camera_samples);
  const double rays = double(r.rays.total());
  const double rays_per_s = rays / r.plain.seconds;
  char per_sample[64];
  std::snprintf(per_sample, sizeof per_sample, "%.2f (%.2f + %.2f)", rays / samples,
                double(r.rays.intersect) / samples, double(r.rays.occluded) / samples);
  std::printf("| %4d | %8.3f | %10.3f | %-26s | %7.2f |", r.spp, r.plain.seconds, samples / r.plain.seconds * 1e-6,
              per_sample, rays_per_s * 1e-6);
  if (r.replay) {
    const double ceiling = double(r.replay->rays) / r.replay->seconds;
    std::printf(" %15.2f | %16.3f |", ceiling * 1e-6, rays_per_s / ceiling);
  } else {
    std::printf(" %15s | %16s |", "not recorded", "-");
  }
  std::printf(" %18.2f | %8.1f |\n", r.decorated_s / r.plain.seconds, r.peak_mib);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parse_options(argc, argv);
    SpectralLibrary library = SpectralLibrary::at_default_location();
    const std::filesystem::path scene_path = options.scene ? *options.scene : default_scene_path(library);
    std::unique_ptr<Scene> scene = load_scene(scene_path, library);
    if (options.resolution) std::tie(scene->settings.width, scene->settings.height) = *options.resolution;
    const uint64_t seed = options.seed.value_or(scene->settings.seed);
    if (options.sampler) scene->settings.sampler = *options.sampler;
    const PixelFilter filter = bench::make_filter(scene->settings.filter);
    const int cores = int(std::thread::hardware_concurrency());
    std::vector<int> thread_counts = options.threads;
    if (thread_counts.empty()) thread_counts = cores > 1 ? std::vector<int>{1, cores} : std::vector<int>{1};

    std::string command;
    for (int i = 0; i < argc; ++i) {
      if (i > 0) command += ' ';
      command += argv[i];
    }
    std::printf("command: %s\n", command.c_str());
    std::printf("machine: %s, %d logical cores, ISA:%s\n", bench::cpu_model().c_str(), cores, vector_isas().c_str());
    std::printf("build:   %s; Embree %s\n", RIMU_BENCH_BUILD, RTC_VERSION_STRING);
    std::printf("scene:   %s, %dx%d, seed %llu, %s sampler, max depth %d\n", scene_path.string().c_str(),
                scene->settings.width, scene->settings.height, (unsigned long long)seed,
                sampler_kind_name(scene->settings.sampler), scene->settings.integrator.max_depth);
    std::printf("peak memory: %s\n",
                reset_peak_memory() ? "VmHWM of each row's plain render (reset through /proc/self/clear_refs)"
                                    : "VmHWM since the process started (could not reset it)");

    bool ok = true;
    for (const int threads : thread_counts) {
      {  // warm-up: TBB's threads, page faults of the film and the scene's first touches stay out of the table
        Row warm;
        ok &= run_row(library, *scene, filter, 1, threads, seed, false, warm);
      }
      std::printf("\nthreads %d; load average before: %s\n\n", threads, bench::load_average().c_str());
      std::printf("|  spp |   wall s | Msamples/s | rays/sample (isect + occl) | Mrays/s | ceiling Mrays/s | "
                  "renderer/ceiling | counted/plain time | peak MiB |\n");
      std::printf("|-----:|---------:|-----------:|:---------------------------|--------:|----------------:|"
                  "-----------------:|-------------------:|---------:|\n");
      for (const int spp : options.spp) {
        Row row;
        ok &= run_row(library, *scene, filter, spp, threads, seed, spp <= options.record_max_spp, row);
        print_row(row);
      }
      std::printf("\nload average after: %s\n", bench::load_average().c_str());
    }
    return ok ? 0 : 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "rimu-render-bench: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rimu-render-bench: %s\n", e.what());
    return 2;
  }
}
