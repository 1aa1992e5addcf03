// Determinism and graceful interruption of the whole render loop (render/renderer.h):
// - the same scene, seed and sample count give a bit-identical film on 1 and on 2 threads (every pixel's samples
//   come from (seed, pixel, sample index) and are summed in sample order by one thread);
// - a render interrupted before or during its passes keeps whole passes only (every pixel has the same sample
//   count, one of the pass boundaries 1, 3, 7, 15, 31, 47, ...), reports interrupted, and run_render_job
//   (what `rimu` runs) still writes the EXR, marked "rimu:interrupted" with the spp reached.
#include <doctest/doctest.h>

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "integration_support.h"
#include "render/interrupt_flag.h"
#include "render/progress_reporter.h"
#include "render/render_job.h"

using namespace rimu;
using namespace rimu::test;
namespace fs = std::filesystem;

namespace {

// The pass boundaries of render(): passes of 1, 2, 4, 8, 16, 16, ... samples per pixel (renderer.cpp doubles the
// pass after each one, capped at 16), so whole-pass sample counts are 1, 3, 7, 15, 31, 47, ...
bool is_pass_boundary(int spp) {
  int done = 0, pass = 1;
  while (done < spp) {
    done += pass;
    pass = std::min(pass * 2, 16);
  }
  return done == spp;
}

// Every pixel of the film has exactly `spp` samples (box filter: weight 1 per sample).
bool every_pixel_has(const Film& film, int spp) {
  const PixelBounds& b = film.pixel_bounds();
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x)
      if (film.weight_sum(x, y) != double(spp)) return false;
  return true;
}

// A closure-style scene (diffuse floor, distant light, constant sky) of 64×64 pixels: four 16-pixel tile columns.
nlohmann::json small_scene(int spp) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 2, -2], "to": [0, 0, 0], "vertical_fov_deg": 50},
    "film": {"resolution": [64, 64], "filter": {"type": "box"}},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]},
               {"type": "sphere", "center": [0, 0.4, 0], "radius": 0.4, "material": "floor"}],
    "lights": [{"type": "distant", "direction": [1, 2, -1], "irradiance": 2}, {"type": "environment", "radiance": 0.5}]
  })");
  scene["integrator"]["spp"] = spp;
  return scene;
}

volatile std::sig_atomic_t g_early_signals = 0;
extern "C" void count_early_signal(int) { g_early_signals = g_early_signals + 1; }

}  // namespace

TEST_CASE("determinism: the Cornell box on 1 and on 2 threads gives a bit-identical film") {
  const auto scene = load_scene(default_scene_path(library()), library());
  // A 64×64 crop of the centre (16 tiles, so both threads get work): the blocks, walls and light.
  const PixelBounds crop{96, 96, 160, 160};
  const RenderedFilm one = render_xyz(*scene, 4, 77, 1, crop);
  const RenderedFilm two = render_xyz(*scene, 4, 77, 2, crop);
  const std::vector<double> a = film_bits(*one.film), b = film_bits(*two.film);
  REQUIRE(a.size() == b.size());
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
  CHECK(one.film->sample_counts().accepted == two.film->sample_counts().accepted);
  CHECK(one.film->sample_counts().accepted == uint64_t(64 * 64 * 4));
  // Not trivially equal: a different seed changes the image.
  const RenderedFilm other_seed = render_xyz(*scene, 4, 78, 2, crop);
  const std::vector<double> c = film_bits(*other_seed.film);
  CHECK(std::memcmp(a.data(), c.data(), a.size() * sizeof(double)) != 0);
}

TEST_CASE("interrupt: a stop requested before rendering leaves an empty film marked interrupted") {
  const auto scene = scene_from_json(small_scene(64));
  InterruptFlag flag;
  flag.request();
  const RenderedFilm rendered = render_xyz(*scene, 64, 1, 2, std::nullopt, &flag);
  CHECK(rendered.statistics.interrupted);
  CHECK(rendered.statistics.samples_per_pixel_done == 0);
  CHECK(rendered.film->sample_counts().accepted == 0);
  CHECK(every_pixel_has(*rendered.film, 0));
}

TEST_CASE("interrupt: a stop requested while rendering keeps whole passes only") {
  const auto scene = scene_from_json(small_scene(1 << 20));
  InterruptFlag flag;
  std::FILE* quiet = std::tmpfile();
  ProgressReporter progress(uint64_t(64 * 64) << 20, "rendering", {quiet, 0, 3600.0});
  // Stop once 4 spp over the image were rendered: the first two passes (1 + 2 spp) are merged and the third
  // (4 spp) is in flight, so the render must throw its finished tiles of that pass away (or, if the request
  // comes late, stop after a later pass).
  std::thread stopper([&] {
    while (progress.done() < uint64_t(64 * 64 * 4)) std::this_thread::sleep_for(std::chrono::microseconds(200));
    flag.request();
  });
  FilmOptions options{64, 64, std::nullopt, 0};
  Film film(options, SpectralResponse::cie_xyz(library()));
  RenderOptions render_options;
  render_options.samples_per_pixel = 1 << 20;
  render_options.threads = 2;
  render_options.interrupt = &flag;
  render_options.progress = &progress;
  const RenderStatistics stats = render(*scene, filter_of(*scene), film, render_options);
  stopper.join();
  progress.finish();
  std::fclose(quiet);
  CAPTURE(stats.samples_per_pixel_done);
  CHECK(stats.interrupted);
  CHECK(stats.samples_per_pixel_done >= 3);
  CHECK(stats.samples_per_pixel_done < (1 << 20));
  CHECK(is_pass_boundary(stats.samples_per_pixel_done));
  CHECK(every_pixel_has(film, stats.samples_per_pixel_done));
  CHECK(film.sample_counts().accepted == uint64_t(64 * 64) * uint64_t(stats.samples_per_pixel_done));
  CHECK(stats.camera_samples == film.sample_counts().accepted);
}

TEST_CASE("interrupt: Ctrl-C during run_render_job still writes the EXR, marked interrupted with the spp reached") {
  const fs::path folder = fs::temp_directory_path() / ("rimu-integration-interrupt-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / "scene.json") << small_scene(1 << 24).dump(2);
  RenderJob job;
  job.scene = folder / "scene.json";
  job.exr_output = folder / "out.exr";
  job.quiet = false;  // the summary, which -q leaves out, says "interrupted"
  job.threads = 2;

  // run_render_job installs its own InterruptFlag (a SIGINT handler) after loading the scene. A helper thread
  // waits until that handler has replaced ours, then sends one real SIGINT, as Ctrl-C would. Our own handler
  // catches nothing unless the flag was never installed; it keeps a stray signal from killing the test.
  struct sigaction ours = {}, before = {};
  ours.sa_handler = count_early_signal;
  sigemptyset(&ours.sa_mask);
  sigaction(SIGINT, &ours, &before);
  std::atomic<bool> finished{false};
  std::thread ctrl_c([&] {
    for (;;) {
      if (finished) return;
      struct sigaction now = {};
      sigaction(SIGINT, nullptr, &now);
      if (now.sa_handler != count_early_signal) break;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(30));  // let a few passes finish
    ::kill(::getpid(), SIGINT);
  });
  std::ostringstream log;
  RenderJobResult result;
  try {
    result = run_render_job(job, log);
  } catch (...) {
    finished = true;
    ctrl_c.join();
    sigaction(SIGINT, &before, nullptr);
    throw;
  }
  finished = true;
  ctrl_c.join();
  sigaction(SIGINT, &before, nullptr);

  CHECK(g_early_signals == 0);
  CHECK(result.statistics.interrupted);
  CHECK(is_pass_boundary(result.statistics.samples_per_pixel_done));
  CHECK(log.str().find("interrupted") != std::string::npos);
  REQUIRE(fs::exists(job.exr_output));
  Imf::InputFile file(job.exr_output.c_str());
  const Imf::Header& header = file.header();
  const auto* interrupted = header.findTypedAttribute<Imf::StringAttribute>("rimu:interrupted");
  REQUIRE(interrupted != nullptr);
  CHECK(interrupted->value() ==
        "interrupted at " + std::to_string(result.statistics.samples_per_pixel_done) + " spp");
  CHECK(header.typedAttribute<Imf::IntAttribute>("rimu:spp").value() == result.statistics.samples_per_pixel_done);
  fs::remove_all(folder);
}
