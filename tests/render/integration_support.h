// Helpers of the integration tests (tests/render/integration_*_test.cpp): load a scene from JSON text, render it
// with the real render loop, and the statistics that turn pixel values into error bars.
//
// Why pixels are independent samples: the render loop seeds every (pixel, sample index) on its own
// (transport/sampler.h), so two pixels' estimates share no random numbers. In a region whose expected value is
// the same everywhere, the pixel values are therefore i.i.d. and their spread gives the standard error of their
// mean without any assumption on the integrand.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/film.h"
#include "render/pixel_filter.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "test_support.h"

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
inline PixelFilter filter_of(const Scene& scene) {
  const FilterSettings& f = scene.settings.filter;
  if (f.type == "box") return PixelFilter::box(f.radius_px);
  if (f.type == "blackman-harris") return PixelFilter::blackman_harris(f.radius_px);
  return PixelFilter::gaussian(f.radius_px, f.sigma_px);
}

struct RenderedFilm {
  std::unique_ptr<Film> film;
  RenderStatistics statistics;
};

/// Renders `scene` into a CIE 1931 XYZ film of the scene's resolution (optionally a crop of it).
inline RenderedFilm render_xyz(const Scene& scene, int spp, uint64_t seed, int threads = 2,
                               std::optional<PixelBounds> crop = std::nullopt,
                               const InterruptFlag* interrupt = nullptr) {
  FilmOptions options{scene.settings.width, scene.settings.height, crop, 0};
  RenderedFilm out;
  out.film = std::make_unique<Film>(options, SpectralResponse::cie_xyz(library()));
  RenderOptions render_options;
  render_options.samples_per_pixel = spp;
  render_options.seed = seed;
  render_options.threads = threads;
  render_options.interrupt = interrupt;
  out.statistics = render(scene, filter_of(scene), *out.film, render_options);
  return out;
}

/// The Y (luminance channel) of every pixel of the film's crop window, row by row.
inline std::vector<double> luminance_values(const Film& film) {
  std::vector<double> y;
  const PixelBounds& b = film.pixel_bounds();
  for (int py = b.y0; py < b.y1; ++py)
    for (int px = b.x0; px < b.x1; ++px) y.push_back(film.pixel_value(px, py)[1]);
  return y;
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

/// The mean of a list of values.
inline double mean_of(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / double(values.size());
}

}  // namespace rimu::test
