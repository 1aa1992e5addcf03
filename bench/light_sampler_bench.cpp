// Light sampling benchmark: equal-time relative MSE of the BVH light sampler against the power sampler on five
// scenes (data/scenes/light_sampling/*.json and the Cornell box; `rimu` renders the same files), the room again with
// its window as the sky's portal (both samplers with it; then bvh with it against power without), and the tree's
// build time and memory for 10⁶ emissive triangles. Not a test: timings go to docs/benchmarks.md with the machine,
// its load and the command.
//
// Method. Per scene: a reference rendered with the BVH sampler at --reference-spp; then each sampler renders the
// scene --runs times at --spp, alternating (bvh, power, bvh, ...) so that both see the same machine load, with
// different seeds. relMSE = Σ(Y − Y_ref)² / Σ Y_ref² over the scene's region (film Y); the reference's own noise
// (estimated as the BVH run's relMSE × spp / reference spp) is subtracted from both. Time per sample is the median
// over the runs, in process CPU time (both render threads; the machine is shared, so wall time would also count
// other processes' turns). Monte Carlo error falls as 1/time, so the equal-time ratio is
//   (relMSE_power · t_power) / (relMSE_bvh · t_bvh)   (> 1: the BVH sampler wins by that factor).
//
// Usage: rimu-light-sampler-bench [--spp 16] [--reference-spp 512] [--runs 3] [--resolution 64x48] [--docs]
//        [--scenes 01234567] [--build-only] [--power-spp N] [--spectral]
// --spectral: instead, wavelength-aware choice (bvh-spectral) against bvh on four scenes of coloured lights (red +
// blue lamps, RGB LED panels, sodium + mercury square, the street), same method, with relMSE per film channel X, Y,
// Z and of the chromaticity (x, y): Σ|xy − xy_ref|² / Σ|xy_ref|² over pixels with Y_ref > 0. Chromaticity error is
// a ratio of noisy sums, not exactly ∝ 1/spp; at these noise levels it is close, and the ratio is reported as
// measured. The reference is rendered with bvh. Scenes 0-3 use the visible wavelength density, 4-7 the same scenes
// with "wavelength_density": "lights" (--scenes picks by index; with --spectral the default 01234 runs 0-4, so pass 01234567;
// without it the default runs all eight).
// --power-spp gives the power sampler its own spp (default --spp), so that a light it starves is picked at all;
// the equal-time ratio then compares relMSE · spp · (time per sample).
#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <functional>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bench_support.h"
#include "render/camera/camera.h"
#include "render/film/film.h"
#include "render/scene/json_cursor.h"
#include "render/render_job.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "spectral/error.h"
#include "transport/lights/area_light.h"
#include "transport/lights/bvh_light_sampler.h"

using namespace rimu;
using json = nlohmann::json;

namespace {

struct Settings {
  int spp = 16, reference_spp = 512, runs = 3, width = 64, height = 48;
  int power_spp = 0;  // the power sampler's spp, if not --spp: enough that it picks a starved light at all
  bool docs = false;
  bool build_only = false;  // only the 10⁶-triangle build figures
  bool spectral = false;    // bvh-spectral against bvh on coloured lights
  std::string scenes;       // which scenes, by index; empty: 01234 with --spectral, else 01234567
};

struct BenchScene {
  std::string name;
  json document;
  std::filesystem::path directory;
  // The region the error is measured over: the pixels whose central camera ray hits a point `in_region` accepts
  // (none: the whole image).
  std::function<bool(Vec3)> in_region;
  std::string region_name = "whole image";
  // If set, the power sampler renders this document instead (a baseline without some other improvement).
  std::optional<json> power_document;
};

struct RenderResult {
  std::vector<double> y;  // film Y per pixel, row by row
  std::vector<double> x, z;  // film X and Z likewise
  double seconds = 0;  // process CPU time (both render threads): on a shared machine, the work done
};

std::unique_ptr<Scene> load(const BenchScene& s, const char* sampler, const Settings& settings,
                            SpectralLibrary& library) {
  json d = std::string(sampler) == "power" && s.power_document ? *s.power_document : s.document;
  d["integrator"]["light_sampler"] = sampler;
  d["film"]["resolution"] = {settings.width, settings.height};
  d["film"]["filter"] = {{"type", "box"}};
  return load_scene(d, s.name, s.directory, library);
}

RenderResult render_y(const Scene& scene, int spp, uint64_t seed, SpectralLibrary& library) {
  Film film(FilmOptions{scene.settings.width, scene.settings.height, std::nullopt, 0}, SpectralResponse::cie_xyz(library));
  RenderOptions options;
  options.samples_per_pixel = spp;
  options.seed = seed;
  options.sampler = scene.settings.sampler;
  options.threads = 2;
  const std::clock_t start = std::clock();
  render(scene, bench::make_filter(scene.settings.filter), film, options);
  RenderResult r;
  r.seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
  for (int py = 0; py < scene.settings.height; ++py)
    for (int px = 0; px < scene.settings.width; ++px) {
      const auto v = film.pixel_value(px, py);
      r.x.push_back(v[0]);
      r.y.push_back(v[1]);
      r.z.push_back(v[2]);
    }
  return r;
}

std::vector<bool> region_mask(const Scene& scene, const BenchScene& s) {
  const int w = scene.settings.width, h = scene.settings.height;
  std::vector<bool> mask(size_t(w * h), true);
  if (!s.in_region) return mask;
  const Camera camera(scene.camera, w, h);
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const auto hit = scene.geometry.intersect(camera.generate_ray(float(px) + 0.5f, float(py) + 0.5f, {0.5f, 0.5f}));
      mask[size_t(py * w + px)] = hit && s.in_region(hit->position);
    }
  return mask;
}

double relative_mse(const std::vector<double>& y, const std::vector<double>& reference, const std::vector<bool>& mask) {
  double error = 0, norm = 0;
  for (size_t i = 0; i < y.size(); ++i)
    if (mask[i]) {
      error += (y[i] - reference[i]) * (y[i] - reference[i]);
      norm += reference[i] * reference[i];
    }
  return error / norm;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct SceneResult {
  std::string name, region;
  double rel_mse_bvh, rel_mse_power, time_bvh_us, time_power_us, ratio;
  int power_spp;
};

SceneResult run_scene(const BenchScene& s, const Settings& settings, SpectralLibrary& library) {
  const auto bvh = load(s, "bvh", settings, library);
  const auto power = load(s, "power", settings, library);
  const int power_spp = settings.power_spp > 0 ? settings.power_spp : settings.spp;
  const RenderResult reference = render_y(*bvh, settings.reference_spp, 99, library);
  const std::vector<bool> mask = region_mask(*bvh, s);
  std::vector<double> t_bvh, t_power, e_bvh, e_power;
  for (int r = 0; r < settings.runs; ++r) {
    const RenderResult a = render_y(*bvh, settings.spp, uint64_t(1000 + r), library);
    const RenderResult b = render_y(*power, power_spp, uint64_t(2000 + r), library);
    t_bvh.push_back(a.seconds);
    t_power.push_back(b.seconds);
    e_bvh.push_back(relative_mse(a.y, reference.y, mask));
    e_power.push_back(relative_mse(b.y, reference.y, mask));
  }
  double mean_bvh = 0, mean_power = 0;
  for (int r = 0; r < settings.runs; ++r) {
    mean_bvh += e_bvh[size_t(r)] / settings.runs;
    mean_power += e_power[size_t(r)] / settings.runs;
  }
  // The reference's own noise is in both: E[relMSE] = v/spp + v_ref, v_ref ≈ (relMSE_bvh·spp)/reference_spp.
  const double reference_noise = mean_bvh * settings.spp / settings.reference_spp / (1.0 + double(settings.spp) / settings.reference_spp);
  mean_bvh -= reference_noise;
  mean_power -= reference_noise;
  const double pixels = double(settings.width) * settings.height;
  SceneResult out{s.name, s.region_name, mean_bvh, mean_power, median(t_bvh) / (pixels * settings.spp) * 1e6,
                  median(t_power) / (pixels * power_spp) * 1e6, 0.0, power_spp};
  // relMSE ∝ 1/spp: at equal time each sampler's relMSE would be relMSE · spp · (time per sample) / T.
  out.ratio = (mean_power * power_spp * out.time_power_us) / (mean_bvh * settings.spp * out.time_bvh_us);
  std::cerr << s.name << ": relMSE bvh " << mean_bvh << " power " << mean_power << ", us/sample " << out.time_bvh_us
            << " / " << out.time_power_us << ", equal-time ratio " << out.ratio << "\n";
  return out;
}

// Σ|xy − xy_ref|² / Σ|xy_ref|² over masked pixels with Y_ref > 0 (a pixel with X+Y+Z ≤ 0 counts as xy = 0).
double chromaticity_mse(const RenderResult& r, const RenderResult& reference, const std::vector<bool>& mask) {
  const auto xy = [](double x, double y, double z) {
    const double sum = x + y + z;
    return sum > 0.0 ? std::pair<double, double>{x / sum, y / sum} : std::pair<double, double>{0.0, 0.0};
  };
  double error = 0, norm = 0;
  for (size_t i = 0; i < r.y.size(); ++i) {
    if (!mask[i] || !(reference.y[i] > 0.0)) continue;
    const auto [a, b] = xy(r.x[i], r.y[i], r.z[i]);
    const auto [ra, rb] = xy(reference.x[i], reference.y[i], reference.z[i]);
    error += (a - ra) * (a - ra) + (b - rb) * (b - rb);
    norm += ra * ra + rb * rb;
  }
  return error / norm;
}

struct SpectralResult {
  std::string name;
  std::array<double, 4> spectral{}, bvh{}, ratio{};  // X, Y, Z, chromaticity
  double time_spectral_us = 0, time_bvh_us = 0;
};

// bvh-spectral against bvh on one scene: relMSE per channel and of chromaticity, and the equal-time ratios.
SpectralResult run_spectral_scene(const BenchScene& s, const Settings& settings, SpectralLibrary& library) {
  const auto bvh = load(s, "bvh", settings, library);
  const auto spectral = load(s, "bvh-spectral", settings, library);
  const RenderResult reference = render_y(*bvh, settings.reference_spp, 99, library);
  const std::vector<bool> mask = region_mask(*bvh, s);
  std::vector<double> t_spectral, t_bvh;
  SpectralResult out;
  out.name = s.name;
  for (int r = 0; r < settings.runs; ++r) {
    const RenderResult a = render_y(*spectral, settings.spp, uint64_t(1000 + r), library);
    const RenderResult b = render_y(*bvh, settings.spp, uint64_t(2000 + r), library);
    t_spectral.push_back(a.seconds);
    t_bvh.push_back(b.seconds);
    const std::array<double, 4> ea = {relative_mse(a.x, reference.x, mask), relative_mse(a.y, reference.y, mask),
                                      relative_mse(a.z, reference.z, mask), chromaticity_mse(a, reference, mask)};
    const std::array<double, 4> eb = {relative_mse(b.x, reference.x, mask), relative_mse(b.y, reference.y, mask),
                                      relative_mse(b.z, reference.z, mask), chromaticity_mse(b, reference, mask)};
    for (size_t c = 0; c < 4; ++c) {
      out.spectral[c] += ea[c] / settings.runs;
      out.bvh[c] += eb[c] / settings.runs;
    }
  }
  const double pixels = double(settings.width) * settings.height;
  out.time_spectral_us = median(t_spectral) / (pixels * settings.spp) * 1e6;
  out.time_bvh_us = median(t_bvh) / (pixels * settings.spp) * 1e6;
  for (size_t c = 0; c < 4; ++c) {
    // The reference (bvh) has the bvh runs' noise scaled by spp / reference spp; subtracted from both.
    const double reference_noise =
        out.bvh[c] * settings.spp / settings.reference_spp / (1.0 + double(settings.spp) / settings.reference_spp);
    out.spectral[c] -= reference_noise;
    out.bvh[c] -= reference_noise;
    out.ratio[c] = (out.bvh[c] * out.time_bvh_us) / (out.spectral[c] * out.time_spectral_us);
  }
  std::cerr << s.name << ": relMSE X/Y/Z/xy bvh-spectral " << out.spectral[0] << " " << out.spectral[1] << " "
            << out.spectral[2] << " " << out.spectral[3] << ", bvh " << out.bvh[0] << " " << out.bvh[1] << " "
            << out.bvh[2] << " " << out.bvh[3] << "; us/sample " << out.time_spectral_us << " / " << out.time_bvh_us
            << "\n";
  return out;
}

int spectral_main(const Settings& settings, SpectralLibrary& library) {
  const std::string load_before = bench::load_average();
  const std::filesystem::path dir = library.root() / "scenes" / "light_sampling";
  std::vector<BenchScene> scenes;
  for (const std::string density : {"visible", "lights"})
    for (const auto& [name, file] : std::vector<std::pair<std::string, std::string>>{
             {"red + blue LED lamps", "red_blue_lamps.json"},
             {"RGB LED panels (12 × 6)", "rgb_led_panels.json"},
             {"square: low-/high-pressure sodium + mercury", "sodium_mercury_square.json"},
             {"street, 200 sodium/LED lamps", "street.json"}}) {
      BenchScene scene;
      scene.name = name + ", wavelength density " + density;
      scene.document = parse_json_file(dir / file);
      scene.document["integrator"]["wavelength_density"] = density;
      scene.directory = dir;
      scenes.push_back(scene);
    }
  std::vector<SpectralResult> results;
  for (size_t i = 0; i < scenes.size(); ++i)
    if (settings.scenes.find(char('0' + i)) != std::string::npos)
      results.push_back(run_spectral_scene(scenes[i], settings, library));
  const std::string load_after = bench::load_average();
  std::ostringstream md;
  md << "Command: `build/bin/rimu-light-sampler-bench --spectral --spp " << settings.spp << " --reference-spp "
     << settings.reference_spp << " --runs " << settings.runs << " --resolution " << settings.width << "x"
     << settings.height << (settings.scenes != "01234" ? " --scenes " + settings.scenes : std::string())
     << (settings.docs ? " --docs" : "")
     << "` (Release build; scenes in data/scenes/light_sampling/; whole image; film CIE 1931 XYZ; hero-wavelength "
        "sampling with the visible and with the lights wavelength density, scenes 0-3 and 4-7).\n\n"
     << "Machine: " << bench::machine_description() << "; 2 render threads; load average before " << load_before
     << ", after " << load_after << " (runs alternate; process CPU time, medians over the runs).\n"
     << "Build: " << bench::build_description() << ".\n\n"
     << "| scene | relMSE X, Y, Z, xy: bvh-spectral | relMSE X, Y, Z, xy: bvh | µs/sample spectral / bvh | "
        "equal-time relMSE bvh ÷ bvh-spectral: X, Y, Z, xy |\n|---|---|---|---|---|\n";
  const auto four = [](const std::array<double, 4>& v, const char* format) {
    std::string text;
    for (size_t c = 0; c < 4; ++c) text += (c ? ", " : "") + bench::format(v[c], format);
    return text;
  };
  for (const SpectralResult& r : results)
    md << "| " << r.name << " | " << four(r.spectral, "%.3g") << " | " << four(r.bvh, "%.3g") << " | "
       << bench::format(r.time_spectral_us, "%.3g") << " / " << bench::format(r.time_bvh_us, "%.3g") << " | "
       << four(r.ratio, "%.3g") << " |\n";
  std::cout << md.str();
  if (settings.docs)
    bench::update_docs_section(library.root().parent_path() / "docs" / "benchmarks.md", "light-sampling-spectral",
                               "## Light sampling: wavelength-aware choice against bvh", md.str());
  return 0;
}

struct BuildResult {
  int triangles = 0;
  double build_s, build_cpu_s, bytes_per_light;
  int depth;
  double sample_ns, pmf_ns;
  // sample() again with capped (an option) and unlimited (the default) pruning searches, and the fraction of calls that found
  // no light (the probability the cap loses, plus points where nothing can contribute).
  double sample_uncapped_ns = 0, sample_capped_ns = 0, no_light_capped = 0, no_light_uncapped = 0;
};

// Process CPU time per sample() call over `points` (one thread), and the fraction that returned no light.
std::pair<double, double> time_sample(const BvhLightSampler& sampler, const std::vector<LightSamplingPoint>& points,
                                      const std::vector<float>& u) {
  size_t none = 0;
  const std::clock_t t0 = std::clock();
  for (size_t i = 0; i < points.size(); ++i) none += !sampler.sample(points[i], u[i]);
  const std::clock_t t1 = std::clock();
  return {double(t1 - t0) / CLOCKS_PER_SEC / double(points.size()) * 1e9, double(none) / double(points.size())};
}

// The capped search timed against the default's unlimited one (bvh_light_sampler.h, "Capped search").
constexpr int kSearchCap = 8;

BuildResult million_triangles() {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const int n = 1000000;
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;
  vertices.reserve(3 * size_t(n));
  for (int k = 0; k < n; ++k) {
    const Vec3 c{100 * u(rng), 20 * u(rng), 100 * u(rng)};
    for (int j = 0; j < 3; ++j) {
      indices.push_back(uint32_t(vertices.size()));
      vertices.push_back(c + Vec3{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f} * 0.2f);
    }
  }
  const AreaLight mesh(vertices, indices, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 1.0), false);
  const std::vector<const Light*> lights = {&mesh};
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const BvhLightSampler sampler(lights);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double build_cpu_s = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  // Cost per call at random points.
  const int calls = 200000;
  std::vector<LightSamplingPoint> points;
  for (int i = 0; i < calls; ++i) points.push_back({{100 * u(rng), 20 * u(rng), 100 * u(rng)}, {0, 1, 0}});
  double checksum = 0;
  // Process CPU time (one thread here): the machine is shared, and wall time would count other processes' turns.
  const std::clock_t t0 = std::clock();
  std::vector<std::pair<size_t, LightChoice>> choices;
  for (int i = 0; i < calls; ++i)
    if (const auto c = sampler.sample(points[size_t(i)], u(rng))) choices.push_back({size_t(i), *c});
  const std::clock_t t1 = std::clock();
  for (const auto& [i, c] : choices) checksum += sampler.pmf(points[i], c.light, c.part);
  const std::clock_t t2 = std::clock();
  if (checksum < 0) std::cerr << checksum;
  BuildResult out{n, build_s, build_cpu_s, double(sampler.memory_bytes()) / n, sampler.max_depth(),
                  double(t1 - t0) / CLOCKS_PER_SEC / calls * 1e9,
                  double(t2 - t1) / CLOCKS_PER_SEC / double(std::max<size_t>(choices.size(), 1)) * 1e9};
  // Capped searches (an option) against unlimited ones (the default), same points and numbers, timed in turn.
  std::vector<float> us(static_cast<size_t>(calls));
  for (float& x : us) x = u(rng);
  const BvhLightSampler capped(lights, BvhLightSampler::Importance::broadband, kSearchCap);
  const auto [uncapped_ns, uncapped_none] = time_sample(sampler, points, us);
  const auto [capped_ns, capped_none] = time_sample(capped, points, us);
  out.sample_uncapped_ns = uncapped_ns;
  out.no_light_uncapped = uncapped_none;
  out.sample_capped_ns = capped_ns;
  out.no_light_capped = capped_none;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  CLI::App app{"Light sampling: equal-time relative MSE of the BVH light sampler against the power sampler (with\n"
               "--spectral: bvh-spectral against bvh on coloured lights), and the tree's build for 10^6 triangles.",
               "rimu-light-sampler-bench"};
  std::string resolution;
  app.add_option("--spp", settings.spp, "samples per pixel of each timed run (default 16)")->check(CLI::Range(1, 1 << 20));
  app.add_option("--power-spp", settings.power_spp, "the power sampler's samples per pixel (default: --spp)")
      ->check(CLI::Range(1, 1 << 20));
  app.add_option("--reference-spp", settings.reference_spp, "samples per pixel of the reference (default 512)")
      ->check(CLI::Range(1, 1 << 24));
  app.add_option("--runs", settings.runs, "timed runs per sampler and scene (default 3)")->check(CLI::Range(1, 1000));
  app.add_option("--resolution", resolution, "WxH (default 64x48)");
  app.add_option("--scenes", settings.scenes, "which scenes, by index (default 01234567; with --spectral 01234)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return text.find_first_not_of("0123456789") == std::string::npos ? std::string()
                                                                             : "expected scene indices, e.g. 0124";
          },
          "INDICES"));
  app.add_flag("--build-only", settings.build_only, "only the 10^6-triangle build figures");
  app.add_flag("--spectral", settings.spectral, "bvh-spectral against bvh on coloured lights");
  app.add_flag("--docs", settings.docs, "rewrite this benchmark's section of docs/benchmarks.md");
  bench::parse_command_line(app, argc, argv);
  if (!resolution.empty()) {
    try {
      std::tie(settings.width, settings.height) = parse_resolution(resolution, "--resolution");
    } catch (const InputError& e) {
      std::cerr << e.what() << "\n";
      return 1;
    }
  }
  if (settings.scenes.empty()) settings.scenes = settings.spectral ? "01234" : "01234567";
  SpectralLibrary library = SpectralLibrary::at_default_location();
  if (settings.spectral) return spectral_main(settings, library);
  const std::string load_before = bench::load_average();
  const std::filesystem::path scenes = library.root() / "scenes";
  const std::filesystem::path light_sampling = scenes / "light_sampling";
  const auto scene_file = [&](const std::string& name, const std::filesystem::path& file) {
    BenchScene scene;
    scene.name = name;
    scene.document = parse_json_file(file);
    scene.directory = file.parent_path();
    return scene;
  };
  std::vector<BenchScene> bench_scenes;
  // The spot's pool: floor points within 0.7 m of the spot's axis (its outer cone reaches 0.73 m).
  const auto in_pool = [](Vec3 p) { return p.y < 1e-3f && p.x * p.x + p.z * p.z < 0.49f; };
  for (const std::string floor_m : {"3", "100"}) {
    BenchScene spot = scene_file("spot + D65 environment, " + floor_m + " m floor",
                                 light_sampling / ("spot_" + floor_m + "m_floor.json"));
    spot.in_region = in_pool;
    spot.region_name = "spot's pool (floor within 0.7 m of its axis)";
    bench_scenes.push_back(spot);
  }
  bench_scenes.push_back(scene_file("room, 32 × 32 ceiling panels 2700-6500 K + sky window",
                                    light_sampling / "ceiling_grid_room.json"));
  bench_scenes.push_back(scene_file("street, 200 sodium/LED lamps over 500 m + night sky", light_sampling / "street.json"));
  bench_scenes.push_back(scene_file("Cornell box", scenes / "cornell_box" / "scene.json"));
  // The room again, measured where light sampling matters: pixels whose central ray hits the floor or a wall below
  // 2.7 m. Over the whole image the error is that of the ceiling's panels seen directly (16 spp estimate how much
  // of a pixel an 8 cm panel covers: the same noise under every light sampler), which dwarfs the rest.
  const auto below_ceiling = [](Vec3 p) { return p.y < 2.7f; };
  const std::string below_ceiling_name = "floor and walls below 2.7 m (no panel seen directly)";
  const auto room_file = [&](const std::string& name, const char* file) {
    BenchScene scene = scene_file(name, light_sampling / file);
    scene.in_region = below_ceiling;
    scene.region_name = below_ceiling_name;
    return scene;
  };
  bench_scenes.push_back(room_file("room, the window as the sky's portal (both samplers)", "ceiling_grid_room_portal.json"));
  BenchScene portal_against_none = room_file("room: bvh with the window portal, power without", "ceiling_grid_room_portal.json");
  portal_against_none.power_document = parse_json_file(light_sampling / "ceiling_grid_room.json");
  bench_scenes.push_back(portal_against_none);
  // The room itself over the same region (run by default); then, to see where its error comes from (not run by
  // default: --scenes 89), the room lit by its panels alone (the sky removed) and by the sky alone (the panels'
  // emission removed; they stay as black quads).
  bench_scenes.push_back(room_file("room, 32 × 32 ceiling panels 2700-6500 K + sky window", "ceiling_grid_room.json"));
  BenchScene panels_only = room_file("room, panels only (no sky)", "ceiling_grid_room.json");
  panels_only.document["lights"] = json::array();
  bench_scenes.push_back(panels_only);
  BenchScene sky_only = room_file("room, sky only (panels not emitting)", "ceiling_grid_room.json");
  for (json& shape : sky_only.document["shapes"]) shape.erase("emission");
  bench_scenes.push_back(sky_only);

  std::vector<SceneResult> results;
  for (size_t i = 0; i < bench_scenes.size() && !settings.build_only; ++i)
    if (settings.scenes.find(char('0' + i)) != std::string::npos)
      results.push_back(run_scene(bench_scenes[i], settings, library));
  const bool all_scenes = settings.scenes == "01234567";
  const BuildResult build = settings.build_only || all_scenes ? million_triangles() : BuildResult{};
  const std::string load_after = bench::load_average();

  std::ostringstream md;
  md << "Command: `build/bin/rimu-light-sampler-bench --spp " << settings.spp << " --reference-spp "
     << settings.reference_spp << " --runs " << settings.runs << " --resolution " << settings.width << "x"
     << settings.height
     << (settings.power_spp > 0 ? " --power-spp " + std::to_string(settings.power_spp) : std::string())
     << (settings.scenes != "01234567" ? " --scenes " + settings.scenes : std::string())
     << (settings.docs ? " --docs" : "")
     << "` (Release build; scenes in data/scenes/light_sampling/ and data/scenes/cornell_box/, rendered at the "
     << "resolution above with a box filter).\n\n"
     << "Machine: " << bench::machine_description() << "; 2 render threads; load average before " << load_before
     << ", after " << load_after
     << " (a shared machine: both samplers' runs alternate; times are process CPU time, medians over the runs).\n"
     << "Build: " << bench::build_description() << ".\n\n"
     << "| scene | region | relMSE bvh | relMSE power | µs/sample bvh | µs/sample power | equal-time relMSE power ÷ bvh |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const SceneResult& r : results)
    md << "| " << r.name << " | " << r.region << " | " << bench::format(r.rel_mse_bvh) << " | "
       << bench::format(r.rel_mse_power) << " | " << bench::format(r.time_bvh_us, "%.3g") << " | "
       << bench::format(r.time_power_us, "%.3g") << " | " << bench::format(r.ratio, "%.3g") << " |\n";
  if (build.triangles > 0) md << "\nLight BVH over " << build.triangles << " emissive triangles (random, in a 100 m × 20 m × 100 m box): build "
     << bench::format(build.build_s, "%.3g") << " s wall (" << bench::format(build.build_cpu_s, "%.3g")
     << " s CPU, one thread), " << bench::format(build.bytes_per_light, "%.4g")
     << " bytes per triangle (nodes, leaves, bit trails), depth " << build.depth << "; sample() "
     << bench::format(build.sample_ns, "%.3g") << " ns, pmf() " << bench::format(build.pmf_ns, "%.3g")
     << " ns CPU per call at random points with normal +y. Timed again in turn: sample() with searches capped at "
     << kSearchCap << " node visits (an option) " << bench::format(build.sample_capped_ns, "%.3g")
     << " ns (no light at " << bench::format(100 * build.no_light_capped, "%.3g")
     << " % of the calls); with unlimited searches (the default) " << bench::format(build.sample_uncapped_ns, "%.3g")
     << " ns (no light at " << bench::format(100 * build.no_light_uncapped, "%.3g") << " %).\n";
  std::cout << md.str();
  if (settings.docs)
    bench::update_docs_section(library.root().parent_path() / "docs" / "benchmarks.md", "light-sampling",
                               "## Light sampling: BVH against power", md.str());
  return 0;
}
