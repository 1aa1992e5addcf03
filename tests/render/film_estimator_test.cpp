// The film's estimator: XYZ, camera RGB and spectral bins of a constant radiance, and discarded samples.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "render/film/film.h"
#include "spectral/error.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "spectral/wavelengths/wavelength_range.h"
#include "statistics.h"
#include "test_support.h"

using namespace rimu;

namespace {

// Stratified primary samples u_i = (i + ξ_i)/n with a fixed seed: the way a renderer's sampler feeds
// SampledWavelengths::sample_visible.
std::vector<float> stratified(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xi(0.0, 1.0);
  std::vector<float> u(n);
  for (int i = 0; i < n; ++i) u[i] = std::min(float((i + xi(rng)) / n), std::nextafter(1.0f, 0.0f));
  return u;
}

// ∫ f over 360-830 nm by the trapezoid rule on the 1 nm knots of the CIE tables (the curves' own grid).
template <typename F>
double integral_1nm(F&& f) {
  double sum = 0.0;
  for (int k = 360; k <= 830; ++k) sum += (k == 360 || k == 830 ? 0.5 : 1.0) * f(double(k));
  return sum;
}

// Feeds n samples of a constant unit radiance to a 1x1 film and checks each channel against `expected`.
// The tolerance is five standard errors of the per-sample values, computed here by a scalar reference of the
// estimator (mean over lanes of c(λ_j)/p(λ_j)). The samples are stratified, whose true error is smaller than the
// i.i.d. standard error, so 5 s.e. bounds it with a false-alarm chance below 1e-6. The SSE film and the scalar
// reference must agree to float rounding (each sample rounds to float once per lane sum: 1e-6 relative).
void check_constant_radiance(const SpectralResponse& response, const std::array<double, 3>& expected, int n) {
  Film film(FilmOptions{1, 1, {}, 0}, response);
  std::vector<std::vector<double>> per_sample(3, std::vector<double>(n));
  const std::vector<float> u = stratified(n, 1234);
  for (int i = 0; i < n; ++i) {
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(u[i]);
    film.add_sample(0, 0, Float4(1.0f), lambda);
    for (int c = 0; c < 3; ++c) {
      double v = 0.0;
      for (int j = 0; j < kLaneCount; ++j) v += response.value(c, lambda.lambda_nm(j)) / lambda.pdf()[j];
      per_sample[c][i] = v / kLaneCount;
    }
  }
  CHECK(film.sample_counts().accepted == uint64_t(n));
  CHECK(film.weight_sum(0, 0) == n);
  const auto value = film.pixel_value(0, 0);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(response.channel_names()[c]);
    const auto [mean, standard_error] = test::mean_and_standard_error(per_sample[c]);
    CHECK(value[c] == doctest::Approx(mean).epsilon(1e-6));
    CAPTURE(standard_error);
    CHECK(std::abs(mean - expected[c]) <= 5.0 * standard_error);
  }
}

}  // namespace

TEST_CASE("XYZ film of a constant unit radiance: Y = 1, X and Z the CMF integral ratios") {
  // SpectralResponse normalises by ∫ȳ, so E[Y] = ∫ȳ/∫ȳ = 1 exactly; X → ∫x̄/∫ȳ, Z → ∫z̄/∫ȳ (integrals of the CIE
  // 1931 table, 1 nm). For E these are ≈ 1.0001 and ≈ 1.0003: the CIE scaled the CMFs so E is nearly X = Y = Z.
  const Observer& o = test::library().observer(StandardObserver::cie1931_2deg);
  const double y = integral_1nm([&](double l) { return o.y_bar.value(l); });
  const double x = integral_1nm([&](double l) { return o.x_bar.value(l); }) / y;
  const double z = integral_1nm([&](double l) { return o.z_bar.value(l); }) / y;
  check_constant_radiance(SpectralResponse::cie_xyz(test::library()), {x, 1.0, z}, 20000);

  SUBCASE("1964 10° observer") {
    const Observer& o10 = test::library().observer(StandardObserver::cie1964_10deg);
    const double y10 = integral_1nm([&](double l) { return o10.y_bar.value(l); });
    check_constant_radiance(SpectralResponse::cie_xyz(test::library(), StandardObserver::cie1964_10deg),
                            {integral_1nm([&](double l) { return o10.x_bar.value(l); }) / y10, 1.0,
                             integral_1nm([&](double l) { return o10.z_bar.value(l); }) / y10},
                            20000);
  }
}

TEST_CASE("luminance per unit film Y is 683 lm/W times the integral of ybar") {
  // Σȳ at 1 nm over 360-830 nm = 106.856917 (tests/spectral/colorimetry_test.cpp). The trapezoid rule differs from
  // that sum by (ȳ(360) + ȳ(830))/2 ≈ 2e-6 nm, i.e. 2e-8 relative; 1e-7 allows for it.
  const SpectralResponse xyz = SpectralResponse::cie_xyz(test::library());
  CHECK(xyz.luminance_nits_per_unit_y() == doctest::Approx(kMaxLuminousEfficacy_lm_W * 106.856917).epsilon(1e-7));
  CHECK(xyz.normalisation_nm() == doctest::Approx(106.856917).epsilon(1e-7));
}

TEST_CASE("camera RGB film: the equal-energy white gives G = 1") {
  // Normalised by ∫ḡ, so E[G] = 1; R and B tend to the camera's ∫r̄/∫ḡ and ∫b̄/∫ḡ. The Nikon D850 (PhysLight) is
  // measured at 10 nm over 380-720 nm and zero outside, so these integrals are the trapezoid rule over its knots
  // (exact for the linear interpolation between them), computed here from the normalised curves.
  const SpectralResponse camera = SpectralResponse::camera_rgb(test::library(), "nikon_d850");
  CHECK(camera.kind() == ResponseKind::camera_rgb);
  CHECK(camera.camera_name() == "pbrt_physlight_nikon_d850_10nm");
  CHECK(camera.value(1, 379.9) == 0.0);
  CHECK(camera.value(1, 720.1) == 0.0);
  std::array<double, 3> integral{};
  for (int c = 0; c < 3; ++c)
    for (int l = 380; l < 720; l += 10) integral[c] += 5.0 * (camera.value(c, l) + camera.value(c, l + 10));
  CHECK(integral[1] == doctest::Approx(1.0).epsilon(1e-12));
  check_constant_radiance(camera, integral, 20000);
}

TEST_CASE("camera names: short, full stem, ambiguous and unknown") {
  CHECK(SpectralResponse::camera_short_name("pbrt_physlight_nikon_d850_10nm") == "nikon_d850");
  CHECK(SpectralResponse::camera_short_name("npl_darrodi2015_sigma_sd_merrill_10nm") == "sigma_sd_merrill");
  CHECK(SpectralResponse::camera_short_name("rawtoaces_sony_ilce-7rm2_5nm") == "sony_ilce-7rm2");
  CHECK(SpectralResponse::camera_rgb(test::library(), "rawtoaces_nikon_d5100_5nm").camera_name() ==
        "rawtoaces_nikon_d5100_5nm");
  // "nikon_d5100" was measured by NPL and for rawtoaces: the error names both files.
  CHECK_THROWS_WITH_AS(SpectralResponse::camera_rgb(test::library(), "nikon_d5100"),
                       doctest::Contains("npl_darrodi2015_nikon_d5100_5nm"), InputError);
  CHECK_THROWS_WITH_AS(SpectralResponse::camera_rgb(test::library(), "nikon_d5100"),
                       doctest::Contains("rawtoaces_nikon_d5100_5nm"), InputError);
  CHECK_THROWS_WITH_AS(SpectralResponse::from_spec(test::library(), "camera:leica_m3"),
                       doctest::Contains("known cameras: arri_d21"), InputError);
  CHECK_THROWS_WITH_AS(SpectralResponse::from_spec(test::library(), "rgb"), doctest::Contains("xyz, xyz10"),
                       InputError);
  CHECK(SpectralResponse::from_spec(test::library(), "xyz10").description() == "CIE 1964 10°");
}

TEST_CASE("spectral bins of a constant unit radiance are 1 in every bin") {
  // Bin b receives (1/4) Σ_j 1[λ_j ∈ b]/(p_j Δ), whose expectation is (1/Δ)∫_b 1 dλ = 1. Tolerance: 5 standard
  // errors of each bin's per-sample values (as above); 47 bins at 5 s.e. keep a false alarm below 3e-5.
  constexpr int kBins = 47, kSamples = 40000;
  Film film(FilmOptions{1, 1, {}, kBins}, SpectralResponse::cie_xyz(test::library()));
  const SpectralBinning& binning = film.binning();
  CHECK(binning.bin_width_nm() == 10.0);
  std::vector<std::vector<double>> per_sample(kBins, std::vector<double>(kSamples, 0.0));
  const std::vector<float> u = stratified(kSamples, 99);
  for (int i = 0; i < kSamples; ++i) {
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(u[i]);
    film.add_sample(0, 0, Float4(1.0f), lambda);
    for (int j = 0; j < kLaneCount; ++j) {
      const int bin = int((lambda.lambda_nm(j) - kLambdaMinNm) / binning.bin_width_nm());
      per_sample[bin][i] += 1.0 / (double(lambda.pdf()[j]) * binning.bin_width_nm() * kLaneCount);
    }
  }
  for (int bin = 0; bin < kBins; ++bin) {
    CAPTURE(bin);
    const auto [mean, standard_error] = test::mean_and_standard_error(per_sample[bin]);
    CAPTURE(standard_error);
    CHECK(film.spectral_value(0, 0, bin) == doctest::Approx(mean).epsilon(1e-6));
    CHECK(std::abs(film.spectral_value(0, 0, bin) - 1.0) <= 5.0 * standard_error + 1e-6);
  }
}

TEST_CASE("NaN, Inf and negative samples are discarded, counted by reason, and never written") {
  Film film(FilmOptions{2, 1, {}, 4}, SpectralResponse::cie_xyz(test::library()));
  const SampledWavelengths lambda = SampledWavelengths::sample_visible(0.3f);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  film.add_sample(0, 0, Float4(0.5f), lambda);
  film.add_sample(0, 0, Float4(1.5f), lambda);
  const auto before = film.pixel_value(0, 0);

  film.add_sample(0, 0, Float4(1.0f, nan, 1.0f, 1.0f), lambda);  // NaN radiance
  film.add_sample(0, 0, Float4(1.0f, 1.0f, inf, 1.0f), lambda);  // Inf radiance
  film.add_sample(0, 0, Float4(1.0f, 1.0f, 1.0f, -1e-3f), lambda);  // negative radiance: a bug upstream
  film.add_sample(0, 0, Float4(1.0f), SampledWavelengths(lambda.lambda_nm(), Float4(nan, 1e-3f, 1e-3f, 1e-3f)));
  film.add_sample(0, 0, Float4(1e30f), SampledWavelengths(lambda.lambda_nm(), Float4(1e-10f)));  // L/p overflows
  film.add_sample(0, 0, Float4(1.0f), lambda, nan);  // NaN filter weight
  film.add_sample(1, 0, Float4(-inf), lambda);

  const FilmSampleCounts counts = film.sample_counts();
  CHECK(counts.accepted == 2);
  CHECK(counts.nan == 3);
  CHECK(counts.infinite == 3);
  CHECK(counts.negative == 1);
  CHECK(counts.discarded() == 7);
  const auto after = film.pixel_value(0, 0);
  for (int c = 0; c < 3; ++c) {
    CHECK(std::isfinite(after[c]));
    CHECK(after[c] == before[c]);  // bit-identical: nothing was written
  }
  CHECK(film.weight_sum(0, 0) == 2.0);
  CHECK(film.weight_sum(1, 0) == 0.0);
  CHECK(film.pixel_value(1, 0)[1] == 0.0);
  for (int bin = 0; bin < 4; ++bin) CHECK(std::isfinite(film.spectral_value(0, 0, bin)));

  SUBCASE("a lane with pdf 0 is skipped whatever it holds") {
    SampledWavelengths hero_only = lambda;
    hero_only.terminate_secondary();
    film.add_sample(1, 0, Float4(2.0f, nan, -inf, -1.0f), hero_only);
    CHECK(film.sample_counts().accepted == 3);
    // Only the hero: (1/4)·L·c(λ₀)/(p/4) = L·c(λ₀)/p.
    const SpectralResponse& r = film.response();
    CHECK(film.pixel_value(1, 0)[1] ==
          doctest::Approx(2.0 * r.value(1, lambda.hero_nm()) / lambda.pdf()[0]).epsilon(1e-6));
  }
}

TEST_CASE("film options are validated") {
  const SpectralResponse xyz = SpectralResponse::cie_xyz(test::library());
  CHECK_THROWS_AS(Film(FilmOptions{0, 4, {}, 0}, xyz), InputError);
  CHECK_THROWS_WITH_AS(Film(FilmOptions{4, 4, PixelBounds{2, 2, 5, 3}, 0}, xyz), doctest::Contains("--crop"),
                       InputError);
  CHECK_THROWS_AS(Film(FilmOptions{4, 4, PixelBounds{2, 2, 2, 3}, 0}, xyz), InputError);
  CHECK_THROWS_AS(Film(FilmOptions{4, 4, {}, -1}, xyz), InputError);
  const Film cropped(FilmOptions{8, 6, PixelBounds{2, 1, 5, 4}, 0}, xyz);
  CHECK(cropped.pixel_bounds() == PixelBounds{2, 1, 5, 4});
  CHECK(cropped.make_tile(PixelBounds{0, 0, 4, 4}).bounds() == PixelBounds{2, 1, 4, 4});
}
