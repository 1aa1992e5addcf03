// The speed-against-error report of the wavelength modes, from one command:
//
//   cmake --build build -j2 --target rimu-speed-error-bench && build/bin/rimu-speed-error-bench
//
// Per scene: a converged hero reference (cached in <build>/speed_report, not committed), then every wavelength mode
// (hero, single, independent, rgb; hero and single also with the emission wavelength density, "+lights") at a
// ladder of spp; it prints and writes a CSV (mode, spp, wall s, samples/s, relative MSE, RMSE in XYZ, mean and
// 95th-percentile ΔE2000, worst ColorChecker patch ΔE2000), log-log error-vs-time plots
// (docs/benchmarks/speed_error_<scene>.png), and the section "Speed against error" of
// docs/benchmarks.md (between its
// markers; the rest of the file is left alone). Options: --quick (tiny ladder, for checking the driver),
// --threads N (default 2), --out DIR, --no-docs.
#include <algorithm>
#include <chrono>
#include <cmath>
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
#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/io/csv_table.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "transport/sampling/wavelength_modes.h"

namespace fs = std::filesystem;
using namespace rimu;
using bench::format;

namespace {

// One benchmark scene: its file (relative to the data folder), the light that defines its CIELAB white, and the
// resolution it is rendered at (smaller than the scene's own where that keeps the whole report ≤ ~15 minutes).
struct SceneCase {
  std::string id;
  std::string file;
  std::string white_illuminant;  // a CIE illuminant name, "blackbody:<kelvin>", or "csv:<file>:<column>" relative to the scene
  int width, height;
};

const std::vector<SceneCase> kScenes = {
    {"cornell", "scenes/cornell_box/scene.json", "csv:light_emission.csv:radiance_relative", 128, 128},
    {"colorchecker_d65", "scenes/colorchecker_room/colorchecker_d65.json", "D65", 160, 120},
    {"colorchecker_f11", "scenes/colorchecker_room/colorchecker_f11.json", "F11", 160, 120},
    {"colorchecker_a", "scenes/colorchecker_room/colorchecker_a.json", "A", 160, 120},
    {"colour_bleeding", "scenes/colour_bleeding/scene.json", "D65", 160, 120},
    {"dispersion", "scenes/dispersion/scene.json", "D65", 160, 120},
    {"textured", "scenes/textured/scene.json", "F11", 160, 120},
    // Media (issue 6 scenes, data/scenes/README.md); rgb mode runs them with spectral tracking (docs/media.md).
    {"chromatic_slab", "scenes/media/chromatic_slab.json", "blackbody:6500", 128, 96},
    {"skin", "scenes/media/skin.json", "blackbody:4000", 96, 96},
    {"cloud", "scenes/media/cloud.json", "blackbody:5500", 96, 72},
};
// What is compared: each wavelength mode with the visible wavelength density (the default), and hero and single
// also with the scene's emission density ("integrator.wavelength_density": "lights", docs/sampling.md).
struct Variant {
  WavelengthMode mode;
  WavelengthDensityKind density;
  std::string name() const {
    return std::string(wavelength_mode_name(mode)) + (density == WavelengthDensityKind::lights ? "+lights" : "");
  }
};
const std::vector<Variant> kVariants = {{WavelengthMode::hero, WavelengthDensityKind::visible},
                                        {WavelengthMode::single, WavelengthDensityKind::visible},
                                        {WavelengthMode::independent, WavelengthDensityKind::visible},
                                        {WavelengthMode::rgb, WavelengthDensityKind::visible},
                                        {WavelengthMode::hero, WavelengthDensityKind::lights},
                                        {WavelengthMode::single, WavelengthDensityKind::lights}};

struct Settings {
  std::vector<int> ladder = {1, 4, 16, 64, 256};
  int reference_spp = 2048;  // two independent halves (seeds 1000 and 1001), so its own error can be estimated
  int timing_repeats = 3;    // per scene, 64-spp renders of every variant in alternation, for times per sample
  int threads = 2;
  fs::path out;
  bool docs = true;
  std::vector<std::string> only;  // --scenes a,b: just these (no docs; the targets need all four of theirs)
};

struct Row {
  std::string scene, mode;
  int spp = 0;
  double seconds = 0, samples_per_s = 0;
  ImageError error;
  double worst_patch_de = -1;  // < 0: the scene has no ColorChecker patches
  std::string worst_patch;
};

PixelFilter filter_of(const FilterSettings& f) {
  if (f.type == "box") return PixelFilter::box(f.radius_px);
  if (f.type == "blackman-harris") return PixelFilter::blackman_harris(f.radius_px);
  return PixelFilter::gaussian(f.radius_px, f.sigma_px);
}

std::unique_ptr<Scene> load_case(const SceneCase& c, WavelengthMode mode, SpectralLibrary& library,
                                 WavelengthDensityKind density = WavelengthDensityKind::visible) {
  const fs::path path = library.root() / c.file;
  nlohmann::json document = parse_json_file(path);
  document["integrator"]["wavelengths"] = wavelength_mode_name(mode);
  document["integrator"]["wavelength_density"] = density == WavelengthDensityKind::lights ? "lights" : "visible";
  auto scene = load_scene(document, path.string(), path.parent_path(), library);
  scene->settings.width = c.width;
  scene->settings.height = c.height;
  return scene;
}

XyzImage render_case(const Scene& scene, int spp, uint64_t seed, int threads, SpectralLibrary& library,
                     RenderStatistics* statistics) {
  const bool rgb = scene.settings.integrator.wavelengths == WavelengthMode::rgb;
  Film film(FilmOptions{scene.settings.width, scene.settings.height, std::nullopt, 0},
            rgb ? SpectralResponse::rgb_transport(library) : SpectralResponse::cie_xyz(library));
  RenderOptions options;
  options.samples_per_pixel = spp;
  options.seed = seed;
  options.threads = threads;
  options.sampler = scene.settings.sampler;
  const RenderStatistics s = render(scene, filter_of(scene.settings.filter), film, options);
  if (statistics) *statistics = s;
  return XyzImage::from_film(film);
}

Xyz white_of(const SceneCase& c, SpectralLibrary& library) {
  const Observer& observer = library.observer(StandardObserver::cie1931_2deg);
  if (c.white_illuminant.rfind("csv:", 0) == 0) {
    const std::string rest = c.white_illuminant.substr(4);
    const std::string file = rest.substr(0, rest.find(':')), column = rest.substr(rest.find(':') + 1);
    const CsvTable table = CsvTable::read(library.root() / fs::path(c.file).parent_path() / file);
    return illuminant_xyz(TabulatedSpectrum::from_csv(table, column, Extrapolation::zero), observer);
  }
  if (c.white_illuminant.rfind("blackbody:", 0) == 0)
    return illuminant_xyz(BlackbodySpectrum(std::stod(c.white_illuminant.substr(10)), BlackbodySpectrum::Scale::peak_one),
                          observer);
  return illuminant_xyz(*library.illuminant(c.white_illuminant), observer);
}

// Per pixel, the ColorChecker patch its centre sees directly (material index), or −1.
std::vector<int> patch_groups(const Scene& scene) {
  const Camera camera(scene.camera, scene.settings.width, scene.settings.height);
  const TransportScene view = scene.transport_view();
  std::vector<int> groups;
  for (int y = 0; y < scene.settings.height; ++y)
    for (int x = 0; x < scene.settings.width; ++x) {
      const auto hit = view.geometry->intersect(camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f, {0.5f, 0.5f}));
      const bool patch = hit && hit->material >= 0 && scene.material_names[size_t(hit->material)].rfind("patch", 0) == 0;
      groups.push_back(patch ? hit->material : -1);
    }
  return groups;
}

// The worst patch's CIEDE2000 between the patch means of two images (each patch averaged first, which removes
// most of the noise: a patch covers ~150 pixels).
std::pair<double, std::string> worst_patch(const XyzImage& image, const XyzImage& reference, const Xyz& white,
                                           const std::vector<int>& groups, const Scene& scene) {
  const auto a = group_means(image, groups), r = group_means(reference, groups);
  double worst = -1;
  std::string name;
  for (const auto& [group, xyz] : r) {
    const double de = delta_e_2000(lab_of(a.at(group), white), lab_of(xyz, white));
    if (de > worst) {
      worst = de;
      name = scene.material_names[size_t(group)];
    }
  }
  return {worst, name};
}

// log-log interpolation of relMSE against spp along a ladder; outside it, extrapolates with slope −1 (relMSE ∝ 1/spp).
// The ladder's images are deterministic (fixed seeds), so this is a function of spp alone, free of timing noise.
double error_at_spp(const std::vector<Row>& rows, double spp) {
  if (rows.empty()) return NAN;
  if (spp <= rows.front().spp) return rows.front().error.relative_mse * rows.front().spp / spp;
  for (size_t i = 1; i < rows.size(); ++i)
    if (spp <= rows[i].spp) {
      const double x0 = std::log(double(rows[i - 1].spp)), x1 = std::log(double(rows[i].spp));
      const double y0 = std::log(rows[i - 1].error.relative_mse), y1 = std::log(rows[i].error.relative_mse);
      if (!std::isfinite(y0) || !std::isfinite(y1))  // a rung at relMSE 0 (below the reference's own noise)
        return rows[i].error.relative_mse;
      return std::exp(y0 + (y1 - y0) * (std::log(spp) - x0) / (x1 - x0));
    }
  return rows.back().error.relative_mse * rows.back().spp / spp;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

void write_plot(const std::string& id, const std::map<std::string, std::vector<Row>>& by_mode, const fs::path& png) {
  std::map<std::string, std::vector<bench::ErrorTimePoint>> series;
  for (const auto& [mode, rows] : by_mode)
    for (const Row& r : rows) series[mode].push_back({r.seconds, r.error.relative_mse, r.spp});
  bench::draw_error_time_plot("Wavelength modes, speed against error: " + id, series, png);
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  std::string command = "rimu-speed-error-bench";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    command += " " + a;
    if (a == "--quick") {
      settings.ladder = {1, 4};
      settings.reference_spp = 16;
      settings.timing_repeats = 1;
    } else if (a == "--threads" && i + 1 < argc) {
      settings.threads = std::atoi(argv[++i]);
      command += std::string(" ") + argv[i];
    } else if (a == "--out" && i + 1 < argc) {
      settings.out = argv[++i];
      command += std::string(" ") + argv[i];
    } else if (a == "--no-docs") {
      settings.docs = false;
    } else if (a == "--scenes" && i + 1 < argc) {
      std::stringstream list(argv[++i]);
      command += std::string(" ") + argv[i];
      for (std::string id; std::getline(list, id, ',');) settings.only.push_back(id);
      settings.docs = false;
    } else {
      std::cerr << "usage: rimu-speed-error-bench [--quick] [--threads N] [--out DIR] [--no-docs] [--scenes id,id]\n";
      return 2;
    }
  }
  if (settings.out.empty()) settings.out = fs::canonical("/proc/self/exe").parent_path().parent_path() / "speed_report";
  fs::create_directories(settings.out);
  const bool quick = settings.reference_spp < 64;

  SpectralLibrary library = SpectralLibrary::at_default_location();
  const fs::path docs_dir = library.root().parent_path() / "docs";
  const fs::path plot_dir = quick ? settings.out : docs_dir / "benchmarks";
  fs::create_directories(plot_dir);
  const auto report_start = std::chrono::steady_clock::now();

  std::ofstream csv(settings.out / "speed_error.csv");
  csv << "scene,mode,spp,wall_s,samples_per_s,rel_mse,rmse_xyz,mean_de2000,p95_de2000,worst_patch_de2000\n";
  std::printf("%-17s %-11s %5s %8s %11s %10s %10s %8s %8s %8s\n", "scene", "mode", "spp", "wall_s", "samples/s",
              "relMSE", "RMSE_XYZ", "meanDE", "p95DE", "patchDE");

  std::ostringstream md;
  md << "Reproduce with one command (from the repository root; the whole report's duration on the machine below is "
        "at the end of the section; cached references make re-runs shorter):\n\n"
     << "    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2 --target rimu-speed-error-bench"
        " && build/bin/" << command << "\n\n"
     << "- Machine: " << bench::machine_description() << "; " << settings.threads
     << " render threads; load average (1, 5, 15 min) at the start " << bench::load_average()
     << " (the benchmark's own render threads add about their number; other jobs show as the excess).\n"
     << "- Build: " << bench::build_description() << "\n"
     << "- Reference: hero mode, " << settings.reference_spp << " spp as two halves (seeds 1000, 1001; cached in "
        "<build>/speed_report); its own relMSE, estimated from the halves, is subtracted from every relMSE below. "
        "Ladder: spp ∈ {";
  for (size_t i = 0; i < settings.ladder.size(); ++i) md << (i ? ", " : "") << settings.ladder[i];
  md << "}, seed 1, Sobol sampler, every mode on the same scene file (\"wavelengths\" set by the driver).\n"
     << "- relMSE: mean over pixels and X, Y, Z of (v − r)²/(r² + ε²), ε = 0.01·mean reference Y. ΔE2000: per pixel, "
        "CIELAB under the scene's white (its light's chromaticity at the 95th-percentile reference luminance). "
        "Worst patch: CIEDE2000 of the worst ColorChecker patch's mean XYZ (pixels whose centre sees it directly).\n"
     << "- Times per sample: per scene, a 64-spp render of every variant, the variants alternating, repeated "
     << settings.timing_repeats << " times; the median per variant (alternation cancels slow drifts of the machine's "
        "load; the ladder's own wall times in the tables are single runs). The first target is the median of the "
        "per-repeat hero/rgb ratios on the Cornell box.\n"
     << "- Equal time: at hero's median 64-spp time t, variant m affords spp_m = 64·t/t_m samples; its equal-time "
        "relMSE is its ladder's relMSE interpolated log–log at spp_m (the ladder's images are deterministic, so "
        "only the timing is measured twice).\n\n";

  struct Summary {
    double hero_time_per_sample = 0, rgb_time_per_sample = 0, t64 = 0;
    std::map<std::string, std::vector<double>> seconds_64;  // per variant, one per timing repeat
    std::map<std::string, double> equal_time;
    double rgb_bias_rel_mse = 0, rgb_worst_patch = -1, hero_worst_patch = -1;
    std::string rgb_worst_patch_name;
    double rgb_mean_de = 0, hero_mean_de = 0;
  };
  std::map<std::string, Summary> summaries;

  const int timing_spp = std::find(settings.ladder.begin(), settings.ladder.end(), 64) != settings.ladder.end()
                             ? 64 : settings.ladder.back();
  std::vector<SceneCase> scenes;
  for (const SceneCase& c : kScenes)
    if (settings.only.empty() || std::find(settings.only.begin(), settings.only.end(), c.id) != settings.only.end())
      scenes.push_back(c);
  for (const SceneCase& c : scenes) {
    std::unique_ptr<Scene> spectral = load_case(c, WavelengthMode::hero, library);
    std::unique_ptr<Scene> rgb_scene = load_case(c, WavelengthMode::rgb, library);
    std::unique_ptr<Scene> lights_scene = load_case(c, WavelengthMode::hero, library, WavelengthDensityKind::lights);
    const std::vector<int> groups = patch_groups(*spectral);
    const bool has_patches = std::any_of(groups.begin(), groups.end(), [](int g) { return g >= 0; });

    const fs::path cache = settings.out / ("reference_" + c.id + "_" + std::to_string(c.width) + "x" +
                                           std::to_string(c.height) + "_" + std::to_string(settings.reference_spp) + "spp.raw");
    // The reference: two independent halves A and B, averaged. Its own relMSE is ≈ relMSE(A vs B)/4 (the halves'
    // difference has twice a half's variance, the mean half of it), and is subtracted from every row's relMSE:
    // otherwise the reference's noise would be counted as the ladder's error at the top rungs.
    XyzImage half[2];
    for (int h = 0; h < 2; ++h) {
      const fs::path cache = settings.out / ("reference_" + c.id + "_" + std::to_string(c.width) + "x" +
                                             std::to_string(c.height) + "_" + std::to_string(settings.reference_spp) +
                                             "spp_half" + std::to_string(h) + ".raw");
      if (!half[h].read_raw(cache.string()) || half[h].width != c.width || half[h].height != c.height) {
        RenderStatistics s;
        half[h] = render_case(*spectral, settings.reference_spp / 2, 1000 + uint64_t(h), settings.threads, library, &s);
        half[h].write_raw(cache.string());
        std::fprintf(stderr, "%s: reference half %d, %d spp in %.1f s\n", c.id.c_str(), h, settings.reference_spp / 2,
                     s.seconds);
      }
    }
    XyzImage reference = half[0];
    for (size_t i = 0; i < reference.pixels.size(); ++i)
      reference.pixels[i] = {0.5 * (half[0].pixels[i].x + half[1].pixels[i].x),
                             0.5 * (half[0].pixels[i].y + half[1].pixels[i].y),
                             0.5 * (half[0].pixels[i].z + half[1].pixels[i].z)};
    const Xyz white = scene_white(reference, white_of(c, library));
    const double reference_rel_mse = image_error(half[0], half[1], white).relative_mse / 4.0;

    // The loaded scene a variant renders (rgb mode and the emission density change what the loader builds).
    auto scene_of = [&](const Variant& variant) -> Scene& {
      Scene& scene = variant.mode == WavelengthMode::rgb                 ? *rgb_scene
                     : variant.density == WavelengthDensityKind::lights ? *lights_scene
                                                                         : *spectral;
      scene.settings.integrator.wavelengths = variant.mode;
      return scene;
    };
    std::map<std::string, std::vector<Row>> by_mode;
    for (const Variant& variant : kVariants) {
      Scene& scene = scene_of(variant);
      for (int spp : settings.ladder) {
        RenderStatistics s;
        const XyzImage image = render_case(scene, spp, 1, settings.threads, library, &s);
        Row row;
        row.scene = c.id;
        row.mode = variant.name();
        row.spp = spp;
        row.seconds = s.seconds;
        row.samples_per_s = s.seconds > 0 ? double(s.camera_samples) / s.seconds : 0.0;
        row.error = image_error(image, reference, white);
        row.error.relative_mse = std::max(0.0, row.error.relative_mse - reference_rel_mse);
        if (has_patches) std::tie(row.worst_patch_de, row.worst_patch) = worst_patch(image, reference, white, groups, scene);
        std::printf("%-17s %-11s %5d %8.3f %11.4g %10.4g %10.4g %8.3f %8.3f %8.3f\n", c.id.c_str(), row.mode.c_str(),
                    spp, row.seconds, row.samples_per_s, row.error.relative_mse, row.error.rmse_xyz,
                    row.error.mean_delta_e2000, row.error.p95_delta_e2000, row.worst_patch_de);
        std::fflush(stdout);
        csv << c.id << "," << row.mode << "," << spp << "," << row.seconds << "," << row.samples_per_s << ","
            << row.error.relative_mse << "," << row.error.rmse_xyz << "," << row.error.mean_delta_e2000 << ","
            << row.error.p95_delta_e2000 << "," << row.worst_patch_de << "\n";
        by_mode[row.mode].push_back(row);
      }
    }

    // Summary figures: time per sample over the whole ladder; equal-time error at hero's 64-spp time (or its
    // largest ladder point); the rgb bias as the spp-independent term B of relMSE = B + V/spp fitted to the two
    // largest ladder points.
    Summary& sum = summaries[c.id];
    auto time_per_sample = [&](const std::string& mode) {
      double t = 0, n = 0;
      for (const Row& r : by_mode[mode]) t += r.seconds, n += double(r.spp);
      return t / n;
    };
    sum.hero_time_per_sample = time_per_sample("hero");
    sum.rgb_time_per_sample = time_per_sample("rgb");
    const auto& hero_rows = by_mode["hero"];
    for (int rep = 0; rep < settings.timing_repeats; ++rep)
      for (const Variant& variant : kVariants) {
        RenderStatistics s;
        render_case(scene_of(variant), timing_spp, 1, settings.threads, library, &s);
        sum.seconds_64[variant.name()].push_back(s.seconds);
      }
    sum.t64 = median(sum.seconds_64["hero"]);
    for (const auto& [mode, rows] : by_mode)
      sum.equal_time[mode] = error_at_spp(rows, timing_spp * sum.t64 / median(sum.seconds_64[mode]));
    const auto& rgb_rows = by_mode["rgb"];
    if (rgb_rows.size() >= 2) {
      const Row &a = rgb_rows[rgb_rows.size() - 2], &b = rgb_rows.back();
      const double v = (a.error.relative_mse - b.error.relative_mse) / (1.0 / a.spp - 1.0 / b.spp);
      sum.rgb_bias_rel_mse = std::max(0.0, b.error.relative_mse - v / b.spp);
    }
    sum.rgb_worst_patch = rgb_rows.back().worst_patch_de;
    sum.rgb_worst_patch_name = rgb_rows.back().worst_patch;
    sum.hero_worst_patch = hero_rows.back().worst_patch_de;
    sum.rgb_mean_de = rgb_rows.back().error.mean_delta_e2000;
    sum.hero_mean_de = hero_rows.back().error.mean_delta_e2000;

    const fs::path png = plot_dir / ("speed_error_" + c.id + ".png");
    write_plot(c.id, by_mode, png);

    md << "### " << c.id << " (" << c.file << ", " << c.width << "×" << c.height << ")\n\n"
       << "![relative MSE against wall time, " << c.id << "](benchmarks/speed_error_" << c.id << ".png)\n\n"
       << "| mode | spp | wall s | samples/s | relMSE | RMSE XYZ | mean ΔE00 | p95 ΔE00 |"
       << (has_patches ? " worst patch ΔE00 |" : "") << "\n|---|---|---|---|---|---|---|---|"
       << (has_patches ? "---|" : "") << "\n";
    for (const Variant& variant : kVariants)
      for (const Row& r : by_mode[variant.name()]) {
        md << "| " << r.mode << " | " << r.spp << " | " << format(r.seconds, "%.3f") << " | " << format(r.samples_per_s, "%.3g")
           << " | " << format(r.error.relative_mse) << " | " << format(r.error.rmse_xyz) << " | "
           << format(r.error.mean_delta_e2000, "%.3f") << " | " << format(r.error.p95_delta_e2000, "%.3f") << " |";
        if (has_patches) md << " " << format(r.worst_patch_de, "%.2f") << " |";
        md << "\n";
      }
    md << "\nReference's own relMSE (subtracted): " << format(reference_rel_mse) << ". Median " << timing_spp
       << "-spp times (s): ";
    for (const Variant& variant : kVariants) md << variant.name() << " " << format(median(sum.seconds_64[variant.name()]), "%.3f") << "; ";
    md << "equal time (" << format(sum.t64, "%.3f") << " s, hero at " << timing_spp << " spp): relMSE ";
    for (const Variant& variant : kVariants) md << variant.name() << " " << format(sum.equal_time[variant.name()]) << "; ";
    md << "rgb bias (spp-independent relMSE) " << format(sum.rgb_bias_rel_mse) << "; mean ΔE00 at the top of the ladder: rgb "
       << format(sum.rgb_mean_de, "%.3f") << " vs hero " << format(sum.hero_mean_de, "%.3f") << " (hero's is noise only).\n\n";
  }

  // The three targets of the wavelength modes (complete only when every scene ran: a --scenes subset leaves rows "not run").
  auto ran = [&](const std::string& id) {
    return summaries.count(id) && summaries.at(id).equal_time.count("hero") && summaries.at(id).equal_time.count("single");
  };
  const Summary& cornell = summaries["cornell"];
  // Per-repeat hero/rgb ratios of the Cornell box's alternating timing renders (same repeat: about the same load).
  std::vector<double> ratios;
  if (ran("cornell"))
    for (size_t k = 0; k < cornell.seconds_64.at("hero").size(); ++k)
      ratios.push_back(cornell.seconds_64.at("hero")[k] / cornell.seconds_64.at("rgb")[k]);
  std::sort(ratios.begin(), ratios.end());
  const double cost_ratio = ratios.empty() ? NAN : ratios[ratios.size() / 2];
  md << "### Targets\n\n| target | measured | met? |\n|---|---|---|\n"
     << "| hero time per sample ≤ 1.15 × rgb (Cornell box) | " << format(cost_ratio, "%.3f")
     << "× (median of " << ratios.size() << " alternating " << timing_spp << "-spp pairs, min "
     << format(ratios.empty() ? NAN : ratios.front(), "%.3f") << ", max " << format(ratios.empty() ? NAN : ratios.back(), "%.3f")
     << "; over the ladder " << format(cornell.hero_time_per_sample * 1e3, "%.3g")
     << " vs " << format(cornell.rgb_time_per_sample * 1e3, "%.3g") << " ms per spp of the whole image) | "
     << (cost_ratio <= 1.15 ? "met" : "not met") << " |\n";
  for (const char* id : {"cornell", "colorchecker_d65", "colorchecker_f11", "colorchecker_a"}) {
    if (!ran(id)) {
      md << "| equal-time relMSE hero ≤ 0.5 × single (" << id << ") | not run | — |\n";
      continue;
    }
    const Summary& s = summaries[id];
    const double ratio = s.equal_time.at("hero") / s.equal_time.at("single");
    md << "| equal-time relMSE hero ≤ 0.5 × single (" << id << ") | " << format(ratio, "%.3f") << " ("
       << format(s.equal_time.at("hero")) << " vs " << format(s.equal_time.at("single")) << ") | "
       << (ratio <= 0.5 ? "met" : "not met") << " |\n";
  }
  const Summary& f11 = summaries["colorchecker_f11"];
  md << "| rgb bias ≥ 3 ΔE00 on some patch (ColorChecker under F11) | worst patch " << format(f11.rgb_worst_patch, "%.2f")
     << " ΔE00 (" << f11.rgb_worst_patch_name << "; hero at the same spp: " << format(f11.hero_worst_patch, "%.2f")
     << ") | " << (f11.rgb_worst_patch >= 3.0 ? "met" : "not met") << " |\n\n";
  // The wavelength density's effect, at the same equal time (hero-visible's 64-spp wall time of each scene).
  md << "### Wavelength density: visible vs lights\n\n"
        "Equal-time relMSE ratios at each scene's hero 64-spp wall time (< 1: the emission density is better; "
        "docs/sampling.md, \"Wavelength density\").\n\n"
        "| scene | hero+lights / hero | single+lights / single | hero+lights / single+lights |\n|---|---|---|---|\n";
  for (const SceneCase& c : scenes) {
    const auto& e = summaries[c.id].equal_time;
    md << "| " << c.id << " | " << format(e.at("hero+lights") / e.at("hero"), "%.3f") << " | "
       << format(e.at("single+lights") / e.at("single"), "%.3f") << " | "
       << format(e.at("hero+lights") / e.at("single+lights"), "%.3f") << " |\n";
  }
  md << "\n";
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - report_start).count();
  md << "Whole report: " << format(total, "%.0f") << " s (references " << (quick ? "rendered" : "rendered or cached")
     << "); load average at the end " << bench::load_average() << ".\n";

  std::ofstream(settings.out / "speed_error.md") << md.str();
  std::printf("\n%s", md.str().c_str());
  if (settings.docs && !quick) bench::update_docs_section(docs_dir / "benchmarks.md", "speed-error", "## Speed against error: wavelength modes on ten scenes", md.str());
  std::fprintf(stderr, "wrote %s (CSV, plots, markdown)%s\n", settings.out.string().c_str(),
               settings.docs && !quick ? " and docs/benchmarks.md" : "");
  return 0;
}
