// Helpers of the integration tests (tests/render/integration_*_test.cpp): load a scene from JSON text, render it
// with the real render loop, and the statistics that turn pixel values into error bars.
//
// Why pixels are independent samples: the render loop's samplers are pure functions of (seed, pixel, sample
// index, dimension), and different pixels get independent randomisations (PCG seeds for the independent sampler,
// Owen scrambles of the same nets for Sobol', transport/sampling/sobol_sampler.h), so two pixels' estimates are
// independent; within a pixel, Sobol' stratification only lowers the variance of that pixel's mean. In a region whose expected value is
// the same everywhere, the pixel values are therefore i.i.d. and their spread gives the standard error of their
// mean without any assumption on the integrand.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/film/film.h"
#include "render/film/pixel_filter.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "test_support.h"
#include "transport/integrators/path_integrator.h"
#include "transport/sampling/sampler.h"

namespace rimu::test {

/// The statistical bound used by every integration test: |mean − expected| ≤ kSigmas·SE. With 4.5 standard
/// errors a correct renderer fails a (normal) check with probability 7e-6; the seeds are fixed, so a pass is
/// reproducible and a failure points at a real difference rather than at bad luck.
constexpr double kSigmas = 4.5;

/// Loads a scene from a JSON document; relative paths (CSV spectra, meshes) resolve against the data folder.
inline std::unique_ptr<Scene> scene_from_json(const nlohmann::json& document, const std::string& name = "test.json") {
  return load_scene(document, name, library().root(), library());
}

/// The scene's own pixel filter (tests use a box of radius 0.5: pixel value = mean over the pixel's area).
/// The loaded material named `name` (fails the test if there is none).
inline const Material& material_named(const Scene& scene, const std::string& name) {
  const auto at = std::find(scene.material_names.begin(), scene.material_names.end(), name);
  REQUIRE_MESSAGE(at != scene.material_names.end(), "no material " << name);
  return scene.materials[size_t(at - scene.material_names.begin())];
}

inline PixelFilter filter_of(const Scene& scene) {
  const FilterSettings& f = scene.settings.filter;
  if (f.type == "box") return PixelFilter::box(f.radius_px);
  if (f.type == "blackman-harris") return PixelFilter::blackman_harris(f.radius_px);
  return PixelFilter::gaussian(f.radius_px, f.sigma_px);
}

/// A mean with its standard error.
struct Estimate {
  double mean = 0.0;
  double standard_error = 0.0;
};

/// Mean and standard error (sample standard deviation/√n) of i.i.d. values.
inline Estimate estimate_of(const std::vector<double>& values) {
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= double(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return {mean, std::sqrt(squares / double(values.size() - 1) / double(values.size()))};
}

/// Four fixed wavelengths across the visible, for checks lane by lane (their pdf is irrelevant to the integrator).
inline SampledWavelengths fixed_wavelengths() { return {Float4(400.0f, 500.0f, 600.0f, 700.0f), Float4(1.0f / 470.0f)}; }

/// `integrator` (path or volumetric) run directly on `count` camera rays (ray i = `ray_of(i)`), at
/// fixed_wavelengths(): lane j's `count` values are i.i.d. estimates of L(λ_j) averaged over the rays; returns their
/// means and errors.
template <typename Integrator>
std::array<Estimate, 4> integrator_lane_radiance(const Integrator& integrator, const std::function<Ray(int)>& ray_of,
                                                 int count, uint64_t seed) {
  IndependentSampler sampler(seed);
  std::array<std::vector<double>, 4> lanes;
  for (int i = 0; i < count; ++i) {
    sampler.start_pixel_sample(i, 0, uint32_t(i));
    const SampledSpectrum l = integrator.radiance(ray_of(i), fixed_wavelengths(), sampler);
    for (int j = 0; j < 4; ++j) lanes[size_t(j)].push_back(l[j]);
  }
  std::array<Estimate, 4> out;
  for (int j = 0; j < 4; ++j) out[size_t(j)] = estimate_of(lanes[size_t(j)]);
  return out;
}

/// The scene's own path integrator, as integrator_lane_radiance.
inline std::array<Estimate, 4> lane_radiance(const Scene& scene, const std::function<Ray(int)>& ray_of, int count,
                                             uint64_t seed = 11) {
  const TransportScene view = scene.transport_view();
  const PathIntegrator integrator(view, scene.settings.integrator);
  return integrator_lane_radiance(integrator, ray_of, count, seed);
}

/// A ray from `from` towards `to`.
inline Ray ray_between(Vec3 from, Vec3 to) {
  Ray ray;
  ray.origin = from;
  ray.direction = normalize(to - from);
  return ray;
}

struct RenderedFilm {
  std::unique_ptr<Film> film;
  RenderStatistics statistics;
};

/// Renders `scene` into a CIE 1931 XYZ film of the scene's resolution (optionally a crop of it), with a layer per
/// light group of the scene where `light_groups` (else the film has none).
inline RenderedFilm render_xyz(const Scene& scene, int spp, uint64_t seed, int threads = 2,
                               std::optional<PixelBounds> crop = std::nullopt,
                               const InterruptFlag* interrupt = nullptr, bool light_groups = false) {
  FilmOptions options{scene.settings.width, scene.settings.height, crop, 0};
  RenderedFilm out;
  out.film = light_groups
                 ? std::make_unique<Film>(options, SpectralResponse::cie_xyz(library()), scene.light_groups)
                 : std::make_unique<Film>(options, SpectralResponse::cie_xyz(library()));
  RenderOptions render_options;
  render_options.samples_per_pixel = spp;
  render_options.seed = seed;
  render_options.sampler = scene.settings.sampler;
  render_options.threads = threads;
  render_options.interrupt = interrupt;
  out.statistics = render(scene, filter_of(scene), *out.film, render_options);
  return out;
}

/// Every accumulator of the film (channel sums and weights) over its crop window as raw doubles, for a bitwise
/// comparison.
inline std::vector<double> film_bits(const Film& film) {
  std::vector<double> out;
  const PixelBounds& b = film.pixel_bounds();
  for (int y = b.y0; y < b.y1; ++y) {
    for (int x = b.x0; x < b.x1; ++x) {
      const auto v = film.pixel_value(x, y);
      out.insert(out.end(), v.begin(), v.end());
      out.push_back(film.weight_sum(x, y));
    }
  }
  return out;
}

/// One channel (0 X, 1 Y, 2 Z) of every pixel of the film's crop window, row by row.
inline std::vector<double> channel_values(const Film& film, int channel) {
  std::vector<double> values;
  const PixelBounds& b = film.pixel_bounds();
  for (int py = b.y0; py < b.y1; ++py)
    for (int px = b.x0; px < b.x1; ++px) values.push_back(film.pixel_value(px, py)[size_t(channel)]);
  return values;
}

/// The Y (luminance channel) of every pixel of the film's crop window, row by row.
inline std::vector<double> luminance_values(const Film& film) { return channel_values(film, 1); }


/// The mean of the differences a_i − b_i of two renders of the same pixels (independent across pixels, each pair
/// with mean 0 if the two estimators agree) and its standard error. The pixels need not share an expected value:
/// under the hypothesis of equal means E[(a_i − b_i)²] = Var(a_i − b_i), so Σ(a_i − b_i)²/N² estimates the variance
/// of the mean difference whatever each pixel's own mean and variance are.
inline Estimate paired_difference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double sum = 0.0, squares = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    sum += a[i] - b[i];
    squares += (a[i] - b[i]) * (a[i] - b[i]);
  }
  const double n = double(a.size());
  return {sum / n, std::sqrt(squares) / n};
}

/// Per block×block tile of two width×height images (row-major, pixels independent): |mean paired difference| over its
/// standard error (paired_difference). Two renders of one image with different seeds give values of a standard
/// normal's size; a tile whose value exceeds kSigmas differs beyond noise. A tile with no difference at all gives 0,
/// one with a difference but no spread 1e9.
inline std::vector<double> block_deviations(const std::vector<double>& a, const std::vector<double>& b, int width = 32,
                                            int height = 32, int block = 8) {
  REQUIRE(a.size() == size_t(width) * size_t(height));
  REQUIRE(b.size() == a.size());
  std::vector<double> deviations;
  for (int by = 0; by + block <= height; by += block)
    for (int bx = 0; bx + block <= width; bx += block) {
      std::vector<double> pa, pb;
      for (int y = by; y < by + block; ++y)
        for (int x = bx; x < bx + block; ++x) {
          pa.push_back(a[size_t(y) * size_t(width) + size_t(x)]);
          pb.push_back(b[size_t(y) * size_t(width) + size_t(x)]);
        }
      const Estimate d = paired_difference(pa, pb);
      deviations.push_back(d.standard_error > 0 ? std::abs(d.mean) / d.standard_error : (d.mean == 0 ? 0.0 : 1e9));
    }
  return deviations;
}

/// block_deviations of two 32×32 scenes' luminance, each rendered at 16 spp with its own seed (1 and 2): the
/// comparison of an imported scene with its hand-written equivalent (or a deliberately wrong one).
inline std::vector<double> render_block_deviations(const Scene& a, const Scene& b) {
  return block_deviations(luminance_values(*render_xyz(a, 16, 1).film), luminance_values(*render_xyz(b, 16, 2).film));
}

/// The largest of block_deviations' values.
inline double worst_deviation(const std::vector<double>& deviations) {
  double worst = 0.0;
  for (double d : deviations) worst = std::max(worst, d);
  return worst;
}

/// The sum of every channel of every pixel of `film`, REQUIRE-ing each to be finite (the hard-case tests: nothing
/// non-finite may reach the film, where it would otherwise only be counted and dropped).
inline double finite_total(const Film& film) {
  double total = 0.0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      for (const double v : film.pixel_value(x, y)) {
        REQUIRE(std::isfinite(v));
        total += v;
      }
  return total;
}

/// The mean of a list of values.
inline double mean_of(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / double(values.size());
}

/// The relative mean squared difference of `image` from `reference`, per pixel: (a − b)² / (b² + ε), ε = 1 % of the
/// reference's mean squared (so black pixels do not dominate), averaged over the pixels.
inline double relative_mse(const std::vector<double>& image, const std::vector<double>& reference) {
  const double m = mean_of(reference), floor = 0.01 * m * m;
  double sum = 0.0;
  for (size_t i = 0; i < image.size(); ++i) {
    const double d = image[i] - reference[i];
    sum += d * d / (reference[i] * reference[i] + floor);
  }
  return sum / double(image.size());
}

}  // namespace rimu::test
