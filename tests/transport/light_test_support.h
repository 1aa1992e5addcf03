// Conventions shared by the light and distribution tests: the significance of their chi-square tests (run with
// test::pearson_chi_square(..., Pooling::sparse_into_one) from tests/statistics.h), and Monte Carlo estimates with
// their standard error.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "statistics.h"
#include "transport/lights/light.h"
#include "transport/lights/light_warps.h"

namespace rimu::test {

/// Significance level of every chi-square test here. The seeds are fixed, so a test is deterministic; 1e-3 keeps
/// the chance that a correct sampler was unlucky with the chosen seed small.
inline constexpr double kChiSquareAlpha = 1e-3;

/// A direction uniform on the unit sphere from two draws of `rng` (z from the first, φ from the second), for Monte
/// Carlo integrals over the sphere (∫ p dω = 1 is the mean of 4π·p at such directions).
inline Vec3 uniform_sphere_direction(std::mt19937& rng) {
  return sample_uniform_sphere({uniform01(rng), uniform01(rng)});  // braced: evaluated left to right
}

/// Mean and standard error of the mean of a stream of Monte Carlo samples.
struct MeanEstimate {
  double sum = 0, sum_squares = 0;
  long n = 0;
  void add(double x) {
    sum += x;
    sum_squares += x * x;
    ++n;
  }
  double mean() const { return sum / n; }
  double standard_error() const {
    const double m = mean();
    return std::sqrt(std::max(0.0, sum_squares / n - m * m) / (n - 1));
  }
};

/// How many standard errors a Monte Carlo mean may lie from the exact value: 5σ (a Gaussian two-sided tail of
/// 6e-7), so the check fails only for a real bias, not for an unlucky seed.
inline constexpr double kMonteCarloSigmas = 5.0;

/// Monte Carlo irradiance ∫ L cos θ dω (lane 0 of `lambda`) at `ref` by the light's own sampling, n samples with
/// `seed`; samples below the tangent plane and failed samples count 0. Every sample's density must be finite, > 0.
inline MeanEstimate light_sampling_irradiance(const Light& light, const LightReference& ref,
                                              const SampledWavelengths& lambda, int n, unsigned seed) {
  std::mt19937 rng(seed);
  MeanEstimate e;
  for (int i = 0; i < n; ++i) {
    const auto s = light.sample_li(ref, lambda, {uniform01(rng), uniform01(rng)});
    if (!s) {
      e.add(0.0);
      continue;
    }
    REQUIRE(std::isfinite(s->pdf_solid_angle));
    REQUIRE(s->pdf_solid_angle > 0.0f);
    e.add(s->radiance[0] * std::max(0.0f, dot(s->wi, ref.normal)) / s->pdf_solid_angle);
  }
  return e;
}

}  // namespace rimu::test
