// Hero-wavelength sampling: the visible pdf, its inverse CDF, the rotated partners, and a chi-square test.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/wavelengths/sampled_wavelengths.h"
#include "spectral/wavelengths/wavelength_range.h"
#include "statistics.h"
#include "test_support.h"

using namespace rimu;
using test::chi_square_p_value;
using test::simpson;
using test::uniform01;

namespace {

double pdf(double lambda_nm) { return visible_wavelength_pdf(float(lambda_nm)); }

}  // namespace

TEST_CASE("chi-square p-value helper against closed forms") {
  // For even k, Q(k/2, y) = e^(−y) Σ_{i<k/2} yⁱ/i! (the Poisson CDF); for k = 1, Q = erfc(√(x/2)). These exercise
  // the series (x < a + 1) and the continued fraction (x ≥ a + 1). Both converge to ~1e-15; 1e-12 relative.
  for (const int k : {2, 4, 10, 50}) {
    for (const double x : {0.5, 3.0, 20.0, 49.0, 60.0, 85.0, 150.0}) {
      CAPTURE(k);
      CAPTURE(x);
      double term = 1.0, poisson = 0.0;
      for (int i = 0; i < k / 2; ++i) {
        poisson += term;
        term *= 0.5 * x / (i + 1);
      }
      CHECK(chi_square_p_value(x, k) == doctest::Approx(std::exp(-0.5 * x) * poisson).epsilon(1e-12));
    }
  }
  for (const double x : {0.1, 1.0, 3.84, 10.83}) CHECK(chi_square_p_value(x, 1) == doctest::Approx(std::erfc(std::sqrt(0.5 * x))).epsilon(1e-12));
}

TEST_CASE("the visible pdf integrates to 1 over 360-830 nm and vanishes outside") {
  // Simpson with 4700 intervals (0.1 nm): the pdf's fourth derivative is below 16a⁴·max p ≈ 2e-10/nm⁵, so the
  // quadrature error is < 470 · 0.1⁴ · 2e-10 / 180 ≈ 1e-14. The pdf is returned as float: each value carries
  // ≤ 2⁻²⁴ ≈ 6e-8 relative rounding, which bounds the error of the total; 1e-7 allows for both.
  CHECK(simpson(pdf, kLambdaMinNm, kLambdaMaxNm, 4700) == doctest::Approx(1.0).epsilon(1e-7));
  CHECK(visible_wavelength_pdf(359.9f) == 0.0f);
  CHECK(visible_wavelength_pdf(830.1f) == 0.0f);
  CHECK(visible_wavelength_pdf(std::nanf("")) == 0.0f);
  // The shape: a/(N cosh²(a(λ − 538))) with a = 0.0072/nm (sampled_wavelengths.h), N its integral's normaliser.
  const double a = 0.0072, n = std::tanh(a * (830.0 - 538.0)) - std::tanh(a * (360.0 - 538.0));
  for (const double l : {360.0, 450.5, 538.0, 700.0, 830.0})
    CHECK(pdf(l) == doctest::Approx(a / (n * std::pow(std::cosh(a * (l - 538.0)), 2))).epsilon(2e-7));
  // The Float4 version is the scalar one lane by lane.
  const Float4 lanes = visible_wavelength_pdf(Float4(300.0f, 400.0f, 555.5f, 829.0f));
  CHECK(lanes[0] == visible_wavelength_pdf(300.0f));
  CHECK(lanes[1] == visible_wavelength_pdf(400.0f));
  CHECK(lanes[2] == visible_wavelength_pdf(555.5f));
  CHECK(lanes[3] == visible_wavelength_pdf(829.0f));
}

TEST_CASE("the inverse CDF is consistent with the pdf") {
  // ∫_360^λ(u) p dλ = u. Error budget, all in float: the pdf through expf and three roundings (≤ 4 ulp, 2.4e-7
  // relative, so ≤ 2.4e-7 on the integral), λ through logf (≤ 1 ulp of a log ≤ 4.3: 3.6e-5 nm, times p_max 0.004
  // = 1.4e-7), λ's own rounding (p_max · ulp(λ)/2 ≤ 0.004 · 3.1e-5 = 1.2e-7), t = tanh_low + u·N (3e-8); Simpson
  // negligible (as above). Sum 5.4e-7; bound 1e-6.
  float previous = 0.0f;
  for (int i = 0; i <= 100; ++i) {
    const float u = i < 100 ? float(i) / 100.0f : std::nextafter(1.0f, 0.0f);
    const float lambda = sample_visible_wavelength(u);
    CAPTURE(u);
    CHECK(lambda >= float(kLambdaMinNm));
    CHECK(lambda < float(kLambdaMaxNm));
    CHECK(lambda >= previous);  // monotonic
    previous = lambda;
    CHECK(std::abs(simpson(pdf, kLambdaMinNm, lambda, 2000) - u) <= 1e-6);
  }
  // dλ/du = 1/p(λ): a central difference with δu = 1e-3 resolves λ to ulp(λ)/(2δu/p) ≲ 1.2e-4 relative and has a
  // truncation error of order δu² (tiny): 1e-3 relative.
  for (const float u : {0.01f, 0.2f, 0.5f, 0.77f, 0.99f}) {
    CAPTURE(u);
    const double slope = (double(sample_visible_wavelength(u + 1e-3f)) - sample_visible_wavelength(u - 1e-3f)) /
                         (double(u + 1e-3f) - double(u - 1e-3f));
    CHECK(slope * pdf(sample_visible_wavelength(u)) == doctest::Approx(1.0).epsilon(1e-3));
  }
}

TEST_CASE("sample_visible: hero and partners rotated by a quarter in primary-sample space") {
  std::mt19937 rng(31337);
  std::vector<float> us = {0.0f, 0.25f, 0.5f, 0.75f, std::nextafter(1.0f, 0.0f), std::nextafter(0.75f, 0.0f)};
  for (int i = 0; i < 200; ++i) us.push_back(uniform01(rng));
  for (const float u : us) {
    CAPTURE(u);
    const SampledWavelengths w = SampledWavelengths::sample_visible(u);
    CHECK_FALSE(w.secondary_terminated());
    CHECK(w.hero_nm() == w.lambda_nm(0));
    for (int j = 0; j < kLaneCount; ++j) {
      CAPTURE(j);
      const float lambda = w.lambda_nm(j);
      CHECK(lambda >= float(kLambdaMinNm));
      CHECK(lambda < float(kLambdaMaxNm));
      // Lane j's primary sample is (u + j/4) mod 1: its CDF value, by quadrature, recovers it (same budget as
      // above plus the float rounding of u + j/4, 6e-8).
      const double primary = std::fmod(double(u) + j / 4.0, 1.0);
      const double cdf = simpson(pdf, kLambdaMinNm, lambda, 2000);
      CHECK(std::min(std::abs(cdf - primary), 1.0 - std::abs(cdf - primary)) <= 1.1e-6);
      // The pdf of each lane is the visible pdf at its wavelength, exactly.
      CHECK(w.pdf()[j] == visible_wavelength_pdf(lambda));
      CHECK(w.pdf()[j] > 0.0f);
    }
  }
}

TEST_CASE("chi-square: each lane of sample_visible follows the visible pdf") {
  // 100k primary samples (fixed seed) into 50 bins of 9.4 nm. Expected counts are N ∫_bin p dλ by Simpson, not
  // from the closed-form CDF under test. Each lane is checked on its own: across samples a lane's wavelengths are
  // independent draws, as Pearson's test assumes (the four lanes of one sample are not independent of each other).
  // The test fails if p < 1e-3. (pbrt-v4's bsdfs_test.cpp also rejects on a small significance level, corrected for
  // the number of tests run; here the seed is fixed, so the outcome is deterministic, and four lanes at 1e-3 each
  // keep the family-wise false-alarm rate for a correct sampler below 0.4 %.)
  constexpr int kSamples = 100000, kBins = 50;
  const double bin_nm = (kLambdaMaxNm - kLambdaMinNm) / kBins;
  std::vector<double> expected(kBins), uniform_expected(kBins, double(kSamples) / kBins);
  for (int b = 0; b < kBins; ++b)
    expected[b] = kSamples * simpson(pdf, kLambdaMinNm + b * bin_nm, kLambdaMinNm + (b + 1) * bin_nm, 100);
  std::vector<std::vector<double>> observed(kLaneCount, std::vector<double>(kBins, 0.0));
  std::mt19937 rng(20140625);
  for (int i = 0; i < kSamples; ++i) {
    const SampledWavelengths w = SampledWavelengths::sample_visible(uniform01(rng));
    for (int j = 0; j < kLaneCount; ++j) {
      const int bin = std::min(kBins - 1, int((w.lambda_nm(j) - kLambdaMinNm) / bin_nm));
      observed[j][bin] += 1.0;
    }
  }
  for (int j = 0; j < kLaneCount; ++j) {
    CAPTURE(j);
    const auto [statistic, dof, p_value] = test::pearson_chi_square(observed[j], expected, test::Pooling::adjacent);
    CAPTURE(statistic);
    CHECK(dof == kBins - 1);  // no bin needed pooling: the smallest expected count is ~200
    CHECK(p_value > 1e-3);
    // The test has teeth: the same counts are wildly inconsistent with uniform sampling.
    const double uniform_statistic =
        test::pearson_chi_square(observed[j], uniform_expected, test::Pooling::adjacent).statistic;
    CHECK(chi_square_p_value(uniform_statistic, kBins - 1) < 1e-12);
  }
}

TEST_CASE("Monte Carlo: the four-lane estimator of ∫ȳ dλ is unbiased, with and without partners") {
  // ∫ȳ dλ over 360-830 nm = 106.856917 (Σ ȳ at 1 nm, colorimetry_test; the trapezoid integral of the linearly
  // interpolated ȳ differs by (ȳ(360) + ȳ(830))/2 ≈ 2e-6, far below the Monte Carlo error).
  // Estimator per sample: F = (1/4) Σⱼ ȳ(λⱼ)/p(λⱼ), over lanes with p > 0. With the partners terminated, only the
  // hero remains with density p/4, so F = ȳ(λ₀)/p(λ₀): still unbiased, just noisier. Each mean must lie within
  // 5 standard errors (estimated from the sample variance) of the integral: a false failure has probability
  // ~6e-7. The four-lane SE is ~0.01 (checked below 0.02), so a bias of 0.1 % would be caught; hero-only ~0.3.
  constexpr int kSamples = 100000;
  const Observer& observer = test::library().observer(StandardObserver::cie1931_2deg);
  std::mt19937 rng(4242);
  double total[2] = {0, 0}, total_sq[2] = {0, 0};
  for (int i = 0; i < kSamples; ++i) {
    SampledWavelengths w = SampledWavelengths::sample_visible(uniform01(rng));
    for (int mode = 0; mode < 2; ++mode) {
      if (mode == 1) w.terminate_secondary();
      const Float4 p = w.pdf();
      const Float4 ratio = select(p > Float4(0.0f), observer.y_bar.sample(w) / p, Float4(0.0f));
      const double f = double(sum(ratio)) / kLaneCount;
      total[mode] += f;
      total_sq[mode] += f * f;
    }
  }
  double standard_error[2];
  for (int mode = 0; mode < 2; ++mode) {
    CAPTURE(mode);
    const double mean = total[mode] / kSamples;
    const double variance = (total_sq[mode] - kSamples * mean * mean) / (kSamples - 1);
    standard_error[mode] = std::sqrt(variance / kSamples);
    CAPTURE(mean);
    CAPTURE(standard_error[mode]);
    CHECK(std::abs(mean - 106.856917) <= 5.0 * standard_error[mode]);
  }
  // For this smooth integrand the four rotated lanes average out much of the hero's noise.
  CHECK(standard_error[0] < 0.02);
  CHECK(standard_error[0] < standard_error[1]);
}

TEST_CASE("terminate_secondary keeps the hero with a quarter of its density, once") {
  SampledWavelengths w = SampledWavelengths::sample_visible(0.3f);
  const Float4 lambda_before = w.lambda_nm();
  const float hero_pdf = w.pdf()[0];
  w.terminate_secondary();
  CHECK(w.secondary_terminated());
  CHECK(w.pdf()[0] == hero_pdf / kLaneCount);
  for (int j = 1; j < kLaneCount; ++j) CHECK(w.pdf()[j] == 0.0f);
  for (int j = 0; j < kLaneCount; ++j) CHECK(w.lambda_nm(j) == lambda_before[j]);  // wavelengths untouched
  w.terminate_secondary();  // idempotent: the hero's density is not divided again
  CHECK(w.pdf()[0] == hero_pdf / kLaneCount);
  // Uniform sampling: the pdf is 1/(max − min) in every lane, lanes a quarter of the range apart.
  const SampledWavelengths uniform = SampledWavelengths::sample_uniform(0.1f, 400.0f, 800.0f);
  for (int j = 0; j < kLaneCount; ++j) {
    CHECK(uniform.pdf()[j] == doctest::Approx(1.0 / 400.0).epsilon(1e-7));
    CHECK(uniform.lambda_nm(j) == doctest::Approx(440.0 + 100.0 * j).epsilon(1e-6));
  }
}
