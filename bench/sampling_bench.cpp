// Independent vs low-discrepancy sampling: error against a converged reference along an spp ladder,
// wall time, the MSE ratio at 64 spp and at equal time, and the time per sample ratio, on the measured Cornell box
// (128×128) and the ColorChecker room under D65 (160×120) by default. Prints markdown tables, writes an
// error-vs-time plot per scene (docs/benchmarks/sampling_<scene>.png) and replaces the section between the
// "sampling" markers of docs/benchmarks.md (--no-docs: print only). A plain main(): whole renders.
//
//   build/bin/rimu-sampling-bench [--scene s.json ...] [--resolution WxH] [--max-spp 1024] [--reference-spp 4096]
//                                 [--threads N] [--timing-repeats 3] [--cache DIR] [--no-docs]
//
// The reference is rendered with the Sobol' sampler in two independent halves (seeds 1000003 and 1000033, never
// used by the ladder, whose seed is 1), and cached in DIR (default: <build>/sampling_reference, beside bin/;
// delete it after changing the renderer). Its own squared error is estimated from the halves: for independent
// halves A and B, E|A − B|² = 2σ²_half and the reference (A+B)/2 has σ² = E|A − B|²/4; that floor is printed.
//
// Error measures, over all pixels and the three film channels (CIE XYZ for the default scene):
//   MSE    = mean (x − r)² − (the reference's own MSE): the reference's error is independent of the render's
//            (different seeds), so it adds its own MSE to the measured one; subtracting it removes that floor
//   relMSE = mean (x − r)² / (r² + ε),  ε = 10⁻²·(mean r)²   (Rousselle et al. 2011's relative MSE; the ε keeps
//                                                              dark pixels from dominating)
// A single image's MSE is dominated by a few firefly pixels at low spp, so rows below 64 spp average
// 64/spp renders with seeds 1, 2, …; their wall time is that of one render (the mean).
// Equal time: log MSE is interpolated linearly in log time along the Sobol' ladder at the wall time of the
// independent 64-spp render. Time per sample: the 64-spp renders are repeated, alternating samplers, and the
// median of the per-pair ratios is reported (the machine is shared: alternation cancels slow drifts of its load).
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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
#include "render/render_job.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "spectral/error.h"

using namespace rimu;

namespace {

// A scene to benchmark and its resolution (0 = the scene's own).
struct SceneCase {
  std::filesystem::path file;
  int width = 0, height = 0;
};

struct Options {
  std::vector<SceneCase> scenes;  // empty: the two default scenes
  std::optional<std::filesystem::path> cache;
  std::optional<std::pair<int, int>> resolution;
  int max_spp = 1024, reference_spp = 4096, threads = 0, timing_repeats = 3;
  bool docs = true;
};

Options parse_options(int argc, char** argv) {
  Options o;
  CLI::App app{"Independent against Sobol' sampling: MSE and relative MSE against wall time on a ladder of sample "
               "counts.", "rimu-sampling-bench"};
  std::vector<std::string> scenes;
  std::string resolution, cache;
  bool no_docs = false;
  app.add_option("--scene", scenes, "scene file (repeatable; default: the Cornell box and the ColorChecker room)");
  app.add_option("--resolution", resolution, "WxH (default: each scene's benchmark resolution)");
  app.add_option("--max-spp", o.max_spp, "top of the ladder")->check(CLI::Range(1, 1 << 24));
  app.add_option("--reference-spp", o.reference_spp, "samples per pixel of the reference")->check(CLI::Range(1, 1 << 24));
  app.add_option("--threads", o.threads, "render threads (default: every core)")->check(CLI::Range(1, 1 << 24));
  app.add_option("--timing-repeats", o.timing_repeats, "timed renders per row")->check(CLI::Range(1, 1 << 24));
  app.add_option("--cache", cache, "folder of the cached references (default: <build>/sampling_reference)");
  app.add_flag("--no-docs", no_docs, "do not rewrite docs/benchmarks.md");
  bench::parse_command_line(app, argc, argv);
  for (const std::string& file : scenes) o.scenes.push_back({file, 0, 0});
  if (!resolution.empty()) o.resolution = parse_resolution(resolution, "--resolution");
  if (!cache.empty()) o.cache = cache;
  o.docs = !no_docs;
  return o;
}

// An image: the film's three channels per pixel, row-major.
using Image = std::vector<double>;

struct Render {
  Image image;
  double seconds = 0;
};

Render render_image(SpectralLibrary& library, const Scene& scene, const PixelFilter& filter, SamplerKind sampler,
                    int spp, uint64_t seed, int threads) {
  const RenderSettings& s = scene.settings;
  Film film(FilmOptions{s.width, s.height, std::nullopt, 0}, SpectralResponse::from_spec(library, s.film_response));
  RenderOptions options;
  options.samples_per_pixel = spp;
  options.seed = seed;
  options.threads = threads;
  options.sampler = sampler;
  Render r;
  r.seconds = render(scene, filter, film, options).seconds;
  r.image.reserve(size_t(s.width) * size_t(s.height) * 3);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      for (double c : film.pixel_value(x, y)) r.image.push_back(c);
  return r;
}

struct Reference {
  Image image;
  double own_mse = 0;  // the reference's estimated squared error (see the file comment)
};

double mse(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum / double(a.size());
}

double rel_mse(const Image& x, const Image& r) {
  double mean_r = 0;
  for (double v : r) mean_r += v / double(r.size());
  const double epsilon = 1e-2 * mean_r * mean_r;
  double sum = 0;
  for (size_t i = 0; i < x.size(); ++i) sum += (x[i] - r[i]) * (x[i] - r[i]) / (r[i] * r[i] + epsilon);
  return sum / double(x.size());
}

Reference load_or_render_reference(SpectralLibrary& library, const Scene& scene, const PixelFilter& filter,
                                   const Options& o, const std::filesystem::path& cache_dir, const std::string& stem) {
  const RenderSettings& s = scene.settings;
  const std::filesystem::path file = cache_dir / (stem + "_" + std::to_string(s.width) + "x" + std::to_string(s.height) +
                                                  "_" + std::to_string(o.reference_spp) + "spp.bin");
  const size_t count = size_t(s.width) * size_t(s.height) * 3;
  Reference ref;
  if (std::ifstream in{file, std::ios::binary}) {
    ref.image.resize(count);
    in.read(reinterpret_cast<char*>(&ref.own_mse), sizeof(double));
    in.read(reinterpret_cast<char*>(ref.image.data()), std::streamsize(count * sizeof(double)));
    if (in) {
      std::printf("reference: %s (cached)\n", file.string().c_str());
      return ref;
    }
  }
  const int half = std::max(1, o.reference_spp / 2);
  const Render a = render_image(library, scene, filter, SamplerKind::sobol, half, 1000003, o.threads);
  const Render b = render_image(library, scene, filter, SamplerKind::sobol, half, 1000033, o.threads);
  ref.image.resize(count);
  for (size_t i = 0; i < count; ++i) ref.image[i] = 0.5 * (a.image[i] + b.image[i]);
  ref.own_mse = mse(a.image, b.image) / 4.0;
  std::filesystem::create_directories(cache_dir);
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(&ref.own_mse), sizeof(double));
  out.write(reinterpret_cast<const char*>(ref.image.data()), std::streamsize(count * sizeof(double)));
  std::printf("reference: %s (rendered in %.1f s, cached)\n", file.string().c_str(), a.seconds + b.seconds);
  return ref;
}

struct LadderRow {
  int spp = 0;
  double seconds[2] = {0, 0}, mse[2] = {0, 0}, rel_mse[2] = {0, 0};
};

// log MSE interpolated linearly in log time along a ladder (clamped to its ends; nullopt outside).
std::optional<double> mse_at_time(const std::vector<LadderRow>& rows, int k, double seconds) {
  for (size_t i = 0; i + 1 < rows.size(); ++i) {
    const double t0 = rows[i].seconds[k], t1 = rows[i + 1].seconds[k];
    if (seconds >= t0 && seconds <= t1) {
      const double f = (std::log(seconds) - std::log(t0)) / (std::log(t1) - std::log(t0));
      return std::exp((1 - f) * std::log(rows[i].mse[k]) + f * std::log(rows[i + 1].mse[k]));
    }
  }
  return std::nullopt;
}

// A log-log plot of MSE and relMSE against wall time for both samplers.
void write_plot(const std::vector<LadderRow>& rows, const std::string& id, const std::filesystem::path& png) {
  std::ostringstream data;
  data << "# spp  independent_s  independent_mse  independent_relmse  sobol_s  sobol_mse  sobol_relmse\n";
  for (const LadderRow& r : rows)
    data << r.spp << ' ' << r.seconds[0] << ' ' << r.mse[0] << ' ' << r.rel_mse[0] << ' ' << r.seconds[1] << ' '
         << r.mse[1] << ' ' << r.rel_mse[1] << '\n';
  GnuplotJob job;
  job.terminal = "pngcairo size 800,560 font ',11'";
  job.data_files = {{"ladder.dat", data.str()}};
  job.commands = "set title " + gnuplot_text("Sampling, MSE and relMSE vs wall time: " + id) + " noenhanced\n"
                 "set logscale xy\nset format y '%g'\nset grid\nset key bottom left\n"
                 "set xlabel 'wall time (s)'\nset ylabel 'error vs reference'\n"
                 "plot 'ladder.dat' using 2:3 with linespoints lc 1 title 'independent MSE', \\\n"
                 "     'ladder.dat' using 5:6 with linespoints lc 2 title 'Sobol MSE', \\\n"
                 "     'ladder.dat' using 2:4 with linespoints lc 1 dt 2 title 'independent relMSE', \\\n"
                 "     'ladder.dat' using 5:7 with linespoints lc 2 dt 2 title 'Sobol relMSE'";
  bench::draw_plot(job, png);
}

// The ladder, the 64-spp figures and the timing pairs of one scene, printed and appended to `md`.
void benchmark_scene(SpectralLibrary& library, const SceneCase& c, const Options& o,
                     const std::filesystem::path& cache_dir, const std::filesystem::path& plot_dir, std::ostream& md) {
  std::unique_ptr<Scene> scene = load_scene(c.file, library);
  if (o.resolution) std::tie(scene->settings.width, scene->settings.height) = *o.resolution;
  else if (c.width > 0) scene->settings.width = c.width, scene->settings.height = c.height;
  const PixelFilter filter = bench::make_filter(scene->settings.filter);
  const std::string id = c.file.stem().string() == "scene" ? c.file.parent_path().filename().string()
                                                             : c.file.stem().string();
  std::printf("\nscene:   %s, %dx%d, max depth %d\n", c.file.string().c_str(), scene->settings.width,
              scene->settings.height, scene->settings.integrator.max_depth);
  const Reference ref = load_or_render_reference(library, *scene, filter, o, cache_dir, id);
  double mean_r2 = 0;
  for (double v : ref.image) mean_r2 += v * v / double(ref.image.size());

  // Warm-up: thread pool, page faults, first touches.
  render_image(library, *scene, filter, SamplerKind::sobol, 1, 1, o.threads);

  md << "### " << id << " (" << std::filesystem::relative(c.file, library.root()).string() << ", "
     << scene->settings.width << "×" << scene->settings.height << ")\n\n"
     << "Reference: " << o.reference_spp << " spp (Sobol'), own MSE " << bench::format(ref.own_mse, "%.3g") << " ("
     << bench::format(ref.own_mse / mean_r2, "%.3g") << " of the mean r²), subtracted from every MSE below.\n\n"
     << "|  spp | independent s | Sobol s | independent MSE | Sobol MSE | MSE ratio | independent relMSE | "
        "Sobol relMSE | relMSE ratio |\n"
     << "|-----:|--------------:|--------:|----------------:|----------:|----------:|-------------------:|"
        "-------------:|-------------:|\n";
  const SamplerKind kinds[2] = {SamplerKind::independent, SamplerKind::sobol};
  std::vector<LadderRow> rows;
  for (int spp = 1; spp <= o.max_spp; spp *= 2) {
    LadderRow row;
    row.spp = spp;
    const int repeats = std::max(1, 64 / spp);
    for (int rep = 0; rep < repeats; ++rep)
      for (int k = 0; k < 2; ++k) {
        const Render r = render_image(library, *scene, filter, kinds[k], spp, uint64_t(1 + rep), o.threads);
        row.seconds[k] += r.seconds / repeats;
        row.mse[k] += (mse(r.image, ref.image) - ref.own_mse) / repeats;
        row.rel_mse[k] += rel_mse(r.image, ref.image) / repeats;
      }
    char line[256];
    std::snprintf(line, sizeof line, "| %4d | %13.3f | %7.3f | %15.4g | %9.4g | %9.3f | %18.4g | %12.4g | %12.3f |\n",
                  spp, row.seconds[0], row.seconds[1], row.mse[0], row.mse[1], row.mse[1] / row.mse[0],
                  row.rel_mse[0], row.rel_mse[1], row.rel_mse[1] / row.rel_mse[0]);
    std::fputs(line, stdout);
    std::fflush(stdout);
    md << line;
    rows.push_back(row);
  }
  md << "\n";

  // The two sampling targets at 64 spp, and the equal-time ratio.
  const auto at64 = std::find_if(rows.begin(), rows.end(), [](const LadderRow& r) { return r.spp == 64; });
  if (at64 != rows.end()) {
    std::vector<double> ratios;
    for (int rep = 0; rep < o.timing_repeats; ++rep) {
      const double ti = render_image(library, *scene, filter, SamplerKind::independent, 64, 1, o.threads).seconds;
      const double ts = render_image(library, *scene, filter, SamplerKind::sobol, 64, 1, o.threads).seconds;
      ratios.push_back(ts / ti);
    }
    std::sort(ratios.begin(), ratios.end());
    const double time_ratio = ratios[ratios.size() / 2];
    const double mse_ratio = at64->mse[1] / at64->mse[0];
    md << "* **At 64 spp: MSE Sobol'/independent " << bench::format(mse_ratio, "%.3f")
       << " (target ≤ 0.2: " << (mse_ratio <= 0.2 ? "met" : "not met") << ")**; relMSE ratio "
       << bench::format(at64->rel_mse[1] / at64->rel_mse[0], "%.3f") << ".\n"
       << "* **Time per sample Sobol'/independent " << bench::format(time_ratio, "%.3f") << "** (median of "
       << ratios.size() << " alternating 64-spp pairs; min " << bench::format(ratios.front(), "%.3f") << ", max "
       << bench::format(ratios.back(), "%.3f") << "; target ≤ 1.15: " << (time_ratio <= 1.15 ? "met" : "not met")
       << ").\n";
    if (const auto m = mse_at_time(rows, 1, at64->seconds[0]))
      md << "* Equal time (the independent 64-spp wall time, " << bench::format(at64->seconds[0], "%.3f")
         << " s, on the Sobol' ladder interpolated in log–log): MSE ratio " << bench::format(*m / at64->mse[0], "%.3f")
         << ".\n";
  }
  const std::filesystem::path png = plot_dir / ("sampling_" + id + ".png");
  write_plot(rows, id, png);
  md << "\n![MSE and relMSE vs wall time, " << id << "](benchmarks/sampling_" << id << ".png)\n\n";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options o = parse_options(argc, argv);
    SpectralLibrary library = SpectralLibrary::at_default_location();
    if (o.scenes.empty())
      o.scenes = {{library.root() / "scenes/cornell_box/scene.json", 128, 128},
                  {library.root() / "scenes/colorchecker_room/colorchecker_d65.json", 160, 120}};
    const std::filesystem::path exe_dir = std::filesystem::canonical("/proc/self/exe").parent_path();
    const std::filesystem::path cache_dir = o.cache ? *o.cache : exe_dir.parent_path() / "sampling_reference";
    const std::filesystem::path docs_dir = library.root().parent_path() / "docs";
    const std::filesystem::path plot_dir = o.docs ? docs_dir / "benchmarks" : cache_dir;
    std::filesystem::create_directories(cache_dir);
    std::filesystem::create_directories(plot_dir);
    const auto start = std::chrono::steady_clock::now();

    std::string command = "rimu-sampling-bench";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    std::ostringstream md;
    md << "Reproduce (from the repository root):\n\n"
       << "    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRIMU_BUILD_BENCHMARKS=ON && "
          "cmake --build build -j2 --target rimu-sampling-bench && build/bin/" << command << "\n\n"
       << "* Machine: " << bench::machine_description() << "; render threads " << o.threads
       << " (0 = all); load average (1, 5, 15 min) at the start " << bench::load_average()
       << " (the benchmark's own render threads add about their number; other jobs show as the excess).\n"
       << "* Build: " << bench::build_description() << " (the portable default; no `-march=native`).\n"
       << "* Reference per scene: " << o.reference_spp << " spp with the Sobol' sampler, two halves with seeds "
          "1000003/1000033 (never used by the ladder), cached in <build>/sampling_reference; its own MSE, estimated "
          "from the halves (|A−B|²/4), is subtracted from every MSE.\n"
       << "* MSE = mean over pixels and the XYZ channels of (x − r)²; relMSE = mean (x − r)²/(r² + 10⁻²·mean(r)²). "
          "Rows below 64 spp average 64/spp renders (seeds 1, 2, …) and report their mean wall time.\n\n";
    std::printf("%s", md.str().c_str());
    for (const SceneCase& c : o.scenes) benchmark_scene(library, c, o, cache_dir, plot_dir, md);
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    md << "Whole run: " << bench::format(total, "%.0f") << " s (references rendered or cached); load average at the "
       << "end " << bench::load_average() << ".\n";
    std::printf("\n%s", md.str().c_str());
    if (o.docs) bench::update_docs_section(docs_dir / "benchmarks.md", "sampling", "## Sampling: independent vs Sobol' on the Cornell box and the ColorChecker room", md.str());
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "rimu-sampling-bench: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rimu-sampling-bench: %s\n", e.what());
    return 2;
  }
}
