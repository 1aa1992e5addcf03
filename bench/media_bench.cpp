// The speed-against-error report of participating media, from one command:
//
//   cmake --build build -j2 --target rimu-media-bench && build/bin/rimu-media-bench
//
// Renders the chromatic slab, the skin demo and the cloud (data/scenes/media) with four free-flight estimators:
//   single         one wavelength per path (integrator.wavelengths = single)
//   hero_only      four lanes, the hero's distance density, partners divided by it (no spectral MIS)
//   spectral_mis   four lanes, the hero's distance density, balance heuristic over the lanes' densities
//   tracking       spectral tracking (Kutz et al. 2017 null-collision tracking with history-aware probabilities)
// at a ladder of spp, against a converged spectral_mis reference (cached in <build>/media_report, not committed),
// and prints and writes wall time and relative MSE per (scene, mode, spp), a log-log error-vs-time PNG per
// scene (docs/benchmarks/media_<scene>.png) and the section "Participating media: distance sampling" of
// docs/benchmarks.md (between its markers; the rest of the file is left alone).
// Options: --quick (tiny ladder, no docs), --threads N (default 2), --out DIR, --no-docs.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.h"
#include "render/image/image_error.h"
#include "render/scene/json_cursor.h"
#include "render/renderer.h"
#include "render/scene/scene.h"

namespace fs = std::filesystem;
using namespace rimu;
using bench::format;

namespace {

// A scene and the (small) resolution it is benchmarked at: the whole report must fit in ~10 minutes on 2 cores.
struct SceneCase {
  std::string id, file;
  int width, height;
};
const std::vector<SceneCase> kScenes = {
    {"chromatic_slab", "scenes/media/chromatic_slab.json", 128, 96},
    {"skin", "scenes/media/skin.json", 64, 64},
    {"cloud", "scenes/media/cloud.json", 96, 72},
};

// One estimator: the scene keys it sets.
struct ModeCase {
  std::string id, wavelengths, distance_sampling;
};
const std::vector<ModeCase> kModes = {
    {"single", "single", "spectral_mis"},
    {"hero_only", "hero", "hero_only"},
    {"spectral_mis", "hero", "spectral_mis"},
    {"tracking", "hero", "spectral_tracking"},
};

struct Settings {
  std::vector<int> ladder = {4, 16, 64};
  int reference_spp = 1024;
  int threads = 2;
  fs::path out;
  bool docs = true;
};

struct Row {
  int spp = 0;
  double seconds = 0, relative_mse = 0;
};

std::unique_ptr<Scene> load_case(const SceneCase& c, const ModeCase& mode, SpectralLibrary& library) {
  const fs::path path = library.root() / c.file;
  nlohmann::json document = parse_json_file(path);
  document["integrator"]["wavelengths"] = mode.wavelengths;
  document["integrator"]["distance_sampling"] = mode.distance_sampling;
  auto scene = load_scene(document, path.string(), path.parent_path(), library);
  scene->settings.width = c.width;
  scene->settings.height = c.height;
  return scene;
}

// A box filter of radius 0.5 px: every sample lands in one pixel, so pixel errors are independent.
XyzImage render_case(const Scene& scene, int spp, uint64_t seed, int threads, SpectralLibrary& library,
                     double* seconds) {
  Film film(FilmOptions{scene.settings.width, scene.settings.height, std::nullopt, 0},
            SpectralResponse::cie_xyz(library));
  RenderOptions options;
  options.samples_per_pixel = spp;
  options.seed = seed;
  options.threads = threads;
  options.sampler = scene.settings.sampler;
  const RenderStatistics s = render(scene, PixelFilter::box(0.5f), film, options);
  if (seconds) *seconds = s.seconds;
  return XyzImage::from_film(film);
}

void write_plot(const std::string& id, const std::map<std::string, std::vector<Row>>& by_mode, const fs::path& png) {
  std::map<std::string, std::vector<bench::ErrorTimePoint>> series;
  for (const auto& [mode, rows] : by_mode)
    for (const Row& r : rows) series[mode].push_back({r.seconds, r.relative_mse, r.spp});
  bench::draw_error_time_plot("Participating media, distance sampling: " + id, series, png);
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  CLI::App app{"Participating media: relative MSE against wall time of each distance-sampling mode.", "rimu-media-bench"};
  bool quick = false, no_docs = false;
  std::string out;
  app.add_flag("--quick", quick, "a 1- and 2-spp ladder against a 4-spp reference (a smoke run; no docs)");
  app.add_option("--threads", settings.threads, "render threads")->check(CLI::Range(1, 1 << 20));
  app.add_option("--out", out, "folder of the report and the cached references (default: <build>/media_report)");
  app.add_flag("--no-docs", no_docs, "do not rewrite docs/benchmarks.md");
  const std::string command = bench::parse_command_line(app, argc, argv);
  if (quick) {
    settings.ladder = {1, 2};
    settings.reference_spp = 4;
  }
  settings.docs = !quick && !no_docs;
  settings.out = out;
  if (settings.out.empty()) settings.out = fs::canonical("/proc/self/exe").parent_path().parent_path() / "media_report";
  fs::create_directories(settings.out);

  SpectralLibrary library = SpectralLibrary::at_default_location();
  const fs::path docs_dir = library.root().parent_path() / "docs";
  const fs::path plot_dir = settings.docs ? docs_dir / "benchmarks" : settings.out;
  fs::create_directories(plot_dir);
  const auto report_start = std::chrono::steady_clock::now();

  std::ofstream csv(settings.out / "media_error.csv");
  csv << "scene,mode,spp,wall_s,rel_mse\n";
  std::printf("%-15s %-13s %5s %9s %11s\n", "scene", "mode", "spp", "wall_s", "relMSE");

  std::ostringstream md;
  md << "Reproduce with one command (from the repository root; about 10 minutes on the machine below, references "
        "included):\n\n"
     << "    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2 --target rimu-media-bench"
        " && build/bin/" << command << "\n\n"
     << "- Machine: " << bench::machine_description() << "; "
     << settings.threads << " render threads; load average (1, 5, 15 min) at the start " << bench::load_average()
     << " (the benchmark's own render threads add about their number; other jobs show as the excess).\n"
     << "- Build: " << bench::build_description() << "\n"
     << "- Modes: `single` = `integrator.wavelengths: single` (one wavelength per path); `hero_only`, "
        "`spectral_mis`, `tracking` = `integrator.distance_sampling: hero_only | spectral_mis | spectral_tracking` "
        "with four hero-rotated lanes (docs/media.md). Everything else is the scene file's.\n"
     << "- Reference: `spectral_mis`, " << settings.reference_spp << " spp, seed 1000 (cached in "
        "<build>/media_report). Ladder: spp ∈ {";
  for (size_t i = 0; i < settings.ladder.size(); ++i) md << (i ? ", " : "") << settings.ladder[i];
  md << "}, seed 1, Sobol sampler, box filter of radius 0.5 px (independent pixels).\n"
     << "- relMSE: mean over pixels and X, Y, Z of (v − r)²/(r² + ε²), ε = 0.01·mean reference Y "
        "(render/image/image_error.h). The reference's own noise adds about relMSE(" << settings.reference_spp
     << " spp) to every figure, so ratios between modes at the top of the ladder are what to read.\n\n";

  for (const SceneCase& c : kScenes) {
    const fs::path cache = settings.out / ("reference_" + c.id + "_" + std::to_string(c.width) + "x" +
                                           std::to_string(c.height) + "_" + std::to_string(settings.reference_spp) +
                                           "spp.raw");
    XyzImage reference;
    if (!reference.read_raw(cache.string()) || reference.width != c.width || reference.height != c.height) {
      const auto scene = load_case(c, kModes[2], library);
      double seconds = 0;
      reference = render_case(*scene, settings.reference_spp, 1000, settings.threads, library, &seconds);
      reference.write_raw(cache.string());
      std::fprintf(stderr, "%s: reference %d spp in %.1f s\n", c.id.c_str(), settings.reference_spp, seconds);
    }
    const Xyz white = scene_white(reference, Xyz{0.9505, 1.0, 1.089});  // ΔE is not reported; only relMSE

    std::map<std::string, std::vector<Row>> by_mode;
    for (const ModeCase& mode : kModes) {
      const auto scene = load_case(c, mode, library);
      for (int spp : settings.ladder) {
        Row row;
        row.spp = spp;
        const XyzImage image = render_case(*scene, spp, 1, settings.threads, library, &row.seconds);
        row.relative_mse = image_error(image, reference, white).relative_mse;
        std::printf("%-15s %-13s %5d %9.3f %11.4g\n", c.id.c_str(), mode.id.c_str(), spp, row.seconds,
                    row.relative_mse);
        std::fflush(stdout);
        csv << c.id << "," << mode.id << "," << spp << "," << row.seconds << "," << row.relative_mse << "\n";
        by_mode[mode.id].push_back(row);
      }
    }
    const fs::path png = plot_dir / ("media_" + c.id + ".png");
    write_plot(c.id, by_mode, png);

    md << "### " << c.id << " (" << c.file << ", " << c.width << "×" << c.height << ")\n\n"
       << "![relative MSE against wall time, " << c.id << "](benchmarks/media_" << c.id << ".png)\n\n"
       << "| mode | spp | wall s | relMSE | relMSE × time |\n|---|---|---|---|---|\n";
    for (const ModeCase& mode : kModes)
      for (const Row& r : by_mode[mode.id])
        md << "| " << mode.id << " | " << r.spp << " | " << format(r.seconds, "%.3f") << " | " << format(r.relative_mse)
           << " | " << format(r.relative_mse * r.seconds) << " |\n";
    md << "\n";
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - report_start).count();
  md << "relMSE × time is the inverse efficiency (lower is better) while the error is variance-dominated. "
        "Whole report: " << format(total, "%.0f") << " s; load average at the end "
     << bench::load_average() << ".\n";

  std::ofstream(settings.out / "media_error.md") << md.str();
  std::printf("\n%s", md.str().c_str());
  if (settings.docs) bench::update_docs_section(docs_dir / "benchmarks.md", "media", "## Participating media: distance sampling in the slab, skin and cloud", md.str());
  std::fprintf(stderr, "wrote %s (CSV, plots, markdown)%s\n", settings.out.string().c_str(),
               settings.docs ? " and docs/benchmarks.md" : "");
  return 0;
}
