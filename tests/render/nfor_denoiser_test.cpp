// The denoiser (render/denoise/nfor_denoiser.h) on synthetic images whose answer is known: a constant under Gaussian
// noise with flat features loses most of its error, an edge the albedo shows stays sharp, a noiseless image is left
// alone; and `rimu denoise` refuses files it cannot denoise without writing anything.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "render/denoise/denoise_exr.h"
#include "render/denoise/denoise_inputs.h"
#include "render/denoise/denoise_selection.h"
#include "render/denoise/nfor_denoiser.h"
#include "spectral/error.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// An image whose true colour is `truth(x, y)` (grey) and whose albedo is `albedo(x, y)` (grey); each half is the
// truth plus Gaussian noise of standard deviation sigma_half per channel, so the whole mean has variance
// sigma_half²/2. Normals face +z, depth is 1, every feature is noiseless.
template <typename Truth, typename Albedo>
DenoiseInput synthetic(int w, int h, double sigma_half, Truth truth, Albedo albedo, uint32_t seed) {
  DenoiseInput in;
  in.width = w;
  in.height = h;
  const size_t n = size_t(w) * size_t(h);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (auto& half : in.halves) half.resize(3 * n);
  in.variance.assign(n, float(sigma_half * sigma_half / 2.0));
  in.albedo.resize(3 * n);
  in.normal.resize(3 * n);
  in.depth.assign(n, 1.0f);
  in.albedo_variance.assign(n, 0.0f);
  in.normal_variance.assign(n, 0.0f);
  in.depth_variance.assign(n, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      for (int k = 0; k < 3; ++k) {
        for (auto& half : in.halves) half[3 * p + size_t(k)] = float(truth(x, y) + sigma_half * noise(rng));
        in.albedo[3 * p + size_t(k)] = float(albedo(x, y));
        in.normal[3 * p + size_t(k)] = k == 2 ? 1.0f : 0.0f;
      }
    }
  return in;
}

double mean_squared_error(const std::vector<float>& image, const std::vector<float>& truth) {
  double sum = 0.0;
  for (size_t i = 0; i < image.size(); ++i) sum += (double(image[i]) - truth[i]) * (double(image[i]) - truth[i]);
  return sum / double(image.size());
}

std::vector<float> noisy_mean(const DenoiseInput& in) {
  std::vector<float> out(in.halves[0].size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = 0.5f * (in.halves[0][i] + in.halves[1][i]);
  return out;
}

}  // namespace

TEST_CASE("denoise: a constant under Gaussian noise with flat features") {
  constexpr int kSize = 64;
  constexpr double kSigmaHalf = 0.2, kTruth = 1.0;
  const DenoiseInput in = synthetic(kSize, kSize, kSigmaHalf, [](int, int) { return kTruth; }, [](int, int) { return 0.5; }, 1);
  const DenoiseSettings settings;  // window radius 5: 121 pixels
  const DenoiseResult out = denoise(in, settings);
  const std::vector<float> truth(out.image.size(), float(kTruth));
  const double noisy = mean_squared_error(noisy_mean(in), truth);
  const double denoised = mean_squared_error(out.image, truth);
  // The noisy image's MSE is σ²/2 = 0.02 per value, known to ±1.5 % (12288 values: relative SE √(2/12288)).
  CHECK(noisy == doctest::Approx(kSigmaHalf * kSigmaHalf / 2).epsilon(0.05));
  // A window of N = (2r + 1)² = 225 equally weighted pixels would divide the variance by N. The weights of pure
  // noise are exp(−max(0, d/k²)) with d the variance-cancelled patch distance, whose mean is 0: about half the
  // neighbours have d ≤ 0 and weight 1, the rest less, so the effective count (Σw)²/Σw² stays above N/2 away from
  // the image's edges; the edge pixels (two fifths of a 64² image lie within 7 pixels of an edge), the choice
  // between two bandwidths and the regression's ridge terms cost a little more; the second pass, which filters the
  // result again, gains more than they cost. The bound is N/2 (measured: 265); a filter that
  // averaged a 7×7 neighbourhood (49) fails it.
  const double window = double((2 * settings.window_radius + 1) * (2 * settings.window_radius + 1));
  CAPTURE(noisy / denoised);
  CHECK(noisy / denoised >= window / 2.0);
  // No bias: the denoised mean is the truth within 4 standard errors of the noisy image's mean (it averages the
  // same values; σ_mean/√n = 0.14/√12288 = 1.3e-3).
  double mean = 0.0;
  for (float v : out.image) mean += v;
  mean /= double(out.image.size());
  CHECK(std::fabs(mean - kTruth) < 4.0 * std::sqrt(kSigmaHalf * kSigmaHalf / 2 / double(out.image.size())));
}

TEST_CASE("denoise: an edge present in the albedo stays sharp") {
  // Left half albedo 0.2, right half 0.8; the colour is the albedo (a white light), noise σ_half = 0.1.
  constexpr int kSize = 48, kEdge = 24;
  constexpr double kSigmaHalf = 0.1;
  const auto albedo = [](int x, int) { return x < kEdge ? 0.2 : 0.8; };
  const DenoiseInput in = synthetic(kSize, kSize, kSigmaHalf, albedo, albedo, 2);
  const DenoiseResult out = denoise(in);
  // The mean over each column next to the edge (48 pixels × 3 channels): a blur across the edge would move it by a
  // sizeable part of the 0.6 step (a 15-pixel box filter: 0.3 · 7/15 ≈ 0.28 at the first column). The bound is 4
  // standard errors of the noisy column's mean, σ_half/√2/√144 = 5.9e-3: denoising only lowers that error.
  for (const int x : {kEdge - 1, kEdge}) {
    double mean = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int k = 0; k < 3; ++k) mean += out.image[3 * (size_t(y) * kSize + size_t(x)) + size_t(k)];
    mean /= 3.0 * kSize;
    CAPTURE(x);
    CHECK(std::fabs(mean - albedo(x, 0)) < 4.0 * kSigmaHalf / std::sqrt(2.0) / std::sqrt(3.0 * kSize));
  }
}

TEST_CASE("denoise: a noiseless image changes little") {
  // A smooth gradient with an edge, the same in both halves, variance 0: every neighbour of another colour is
  // excluded, so each pixel keeps its own value (float rounding of the regression only).
  constexpr int kSize = 32;
  const auto truth = [](int x, int y) { return 0.1 + 0.02 * x + 0.01 * y + (x > 20 ? 0.5 : 0.0); };
  const DenoiseInput in = synthetic(kSize, kSize, 0.0, truth, [](int, int) { return 0.5; }, 3);
  const DenoiseResult out = denoise(in);
  for (size_t i = 0; i < out.image.size(); ++i) CHECK(out.image[i] == doctest::Approx(in.halves[0][i]).epsilon(1e-4));
}

TEST_CASE("denoise: a step in the colour alone is not blurred beyond one pixel") {
  // A shadow edge: left half 0.2, right half 0.8, every feature flat, so only the colour weights can stop the filter
  // at the edge. σ_half = 0.05: the step is 8.5 standard errors of one pixel's noisy mean. Every column from one
  // pixel beyond the edge on must keep its level: its mean over 48 rows × 3 channels within 4 standard errors of the
  // noisy column's mean (σ_half/√2/√144 = 2.9e-3); a blur across the edge moves the first columns by a sizeable
  // part of the 0.6 step (a 3-pixel box: 0.2 at the first column, a 15-pixel window's 0.28).
  constexpr int kSize = 48, kEdge = 24;
  constexpr double kSigmaHalf = 0.05;
  const auto truth = [](int x, int) { return x < kEdge ? 0.2 : 0.8; };
  const DenoiseInput in = synthetic(kSize, kSize, kSigmaHalf, truth, [](int, int) { return 0.5; }, 4);
  const DenoiseResult out = denoise(in);
  for (int x = 0; x < kSize; ++x) {
    if (x == kEdge - 1) continue;  // the one pixel allowed: its patch straddles the edge
    double mean = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int k = 0; k < 3; ++k) mean += out.image[3 * (size_t(y) * kSize + size_t(x)) + size_t(k)];
    mean /= 3.0 * kSize;
    CAPTURE(x);
    CHECK(std::fabs(mean - truth(x, 0)) < 4.0 * kSigmaHalf / std::sqrt(2.0) / std::sqrt(3.0 * kSize));
  }
}

TEST_CASE("denoise: a firefly in one half is taken out, a small bright feature in both halves is kept") {
  // Flat grey 1 under noise σ_half = 0.1 (whole mean's variance 0.005). One sample of 200 lands in half 0 of pixel
  // (20, 20): its noisy mean is about 101 and its variance (the renderer's, from its samples) 100². A 2×2 square of
  // true value 4 at (40, 40) is in both halves, with the background's noise: it is real, and the features do not
  // show it (a small light the albedo does not see).
  constexpr int kSize = 64;
  constexpr double kSigmaHalf = 0.1;
  const auto truth = [](int x, int y) { return (x == 40 || x == 41) && (y == 40 || y == 41) ? 4.0 : 1.0; };
  DenoiseInput in = synthetic(kSize, kSize, kSigmaHalf, truth, [](int, int) { return 0.5; }, 5);
  const size_t firefly = 20 * kSize + 20;
  for (int k = 0; k < 3; ++k) in.halves[0][3 * firefly + size_t(k)] += 200.0f;
  in.variance[firefly] = 100.0f * 100.0f;
  const DenoiseResult out = denoise(in);
  // The firefly: nothing within 10 pixels of it stays more than 1 above the background, where the noisy pixel is
  // 100 above it. Its huge variance makes every patch distance to it small, so the cross-filtered half 0 spreads its
  // excess (200) over the ~120 neighbours of effective weight in its 11×11 window: the pixel itself keeps about 1/120
  // of it in half 0's filter, 200/120/2 ≈ 0.8 in the mean of the halves (measured 0.84).
  double worst = 0.0;
  for (int y = 10; y <= 30; ++y)
    for (int x = 10; x <= 30; ++x)
      for (int k = 0; k < 3; ++k) worst = std::max(worst, double(out.image[3 * (size_t(y) * kSize + size_t(x)) + size_t(k)]) - 1.0);
  CAPTURE(worst);
  CHECK(worst < 1.0);
  // The square: its mean over 4 pixels × 3 channels stays within 0.3 of 4 (the noisy mean's standard error is
  // 0.02; a filter that averaged it with its 3×3 neighbourhood would give 2.3, one that ignored the colour 1).
  double square = 0.0;
  for (int y = 40; y <= 41; ++y)
    for (int x = 40; x <= 41; ++x)
      for (int k = 0; k < 3; ++k) square += out.image[3 * (size_t(y) * kSize + size_t(x)) + size_t(k)];
  square /= 12.0;
  CAPTURE(square);
  CHECK(std::fabs(square - 4.0) < 0.3);
}

TEST_CASE("denoise: a black region next to a dim, noisy one stays black") {
  // Left of column 24 a dim surface (0.05) under noise larger than itself (σ_half = 0.1); right of it pixels that
  // no sample lit (0, variance 0), the features the same on both sides. The colour weights alone let the dim side
  // in: its squared distance to 0, 0.05², is a quarter of the noise it is measured against. The clamp to the noisy
  // value ± 5 σ, σ² the median variance of the 3×3 around, holds every pixel two or more columns into the black at
  // exactly 0.
  constexpr int kSize = 48, kEdge = 24;
  const auto truth = [](int x, int) { return x < kEdge ? 0.05 : 0.0; };
  DenoiseInput in = synthetic(kSize, kSize, 0.1, truth, [](int, int) { return 0.5; }, 7);
  for (int y = 0; y < kSize; ++y)
    for (int x = kEdge; x < kSize; ++x) {
      const size_t p = size_t(y) * kSize + size_t(x);
      in.variance[p] = 0.0f;
      for (auto& half : in.halves)
        for (int k = 0; k < 3; ++k) half[3 * p + size_t(k)] = 0.0f;
    }
  const DenoiseResult out = denoise(in);
  double largest = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = kEdge + 1; x < kSize; ++x)
      for (int k = 0; k < 3; ++k) largest = std::max(largest, std::fabs(double(out.image[3 * (size_t(y) * kSize + size_t(x)) + size_t(k)])));
  CAPTURE(largest);
  CHECK(largest == 0.0);
}

TEST_CASE("denoise: the dim channel of a saturated colour stays dim at an albedo edge") {
  // Left of column 24 an orange surface, right of it a cyan one (colour = albedo per channel: a white light); the
  // third channel of the orange and the first of the cyan are 0.02, the others up to 0.8. Noise σ_half = 0.05 in every
  // channel. In the columns on either side of the edge the dim channel's mean over 48 rows must stay within 4
  // standard errors of the noisy column's mean (σ_half/√2/√48 = 5.1e-3) of 0.02: letting 3 % of the other side's
  // 0.8 in moves it by 0.024.
  constexpr int kSize = 48, kEdge = 24;
  constexpr double kSigmaHalf = 0.05;
  const auto colour = [](int x, int k) {
    static constexpr double kOrange[3] = {0.8, 0.4, 0.02}, kCyan[3] = {0.02, 0.4, 0.8};
    return x < kEdge ? kOrange[k] : kCyan[k];
  };
  DenoiseInput in = synthetic(kSize, kSize, kSigmaHalf, [](int, int) { return 0.0; }, [](int, int) { return 0.0; }, 8);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int k = 0; k < 3; ++k) {
        const size_t i = 3 * (size_t(y) * kSize + size_t(x)) + size_t(k);
        for (auto& half : in.halves) half[i] += float(colour(x, k));
        in.albedo[i] = float(colour(x, k));
      }
  const DenoiseResult out = denoise(in);
  for (const int x : {kEdge - 2, kEdge - 1, kEdge, kEdge + 1}) {
    const int dim = x < kEdge ? 2 : 0;
    double mean = 0.0;
    for (int y = 0; y < kSize; ++y) mean += out.image[3 * (size_t(y) * kSize + size_t(x)) + size_t(dim)];
    mean /= kSize;
    CAPTURE(x);
    CHECK(std::fabs(mean - 0.02) < 4.0 * kSigmaHalf / std::sqrt(2.0) / std::sqrt(double(kSize)));
  }
}

TEST_CASE("denoise: the features' prefilter lowers their variance as much as it averages their noise") {
  // A flat albedo of 0.5 under Gaussian noise of variance 10⁻³ per component, reported as its variance; normal and
  // depth noiseless. The prefilter's output variance, Σw²·Var/(Σw)², lies between Var/N (N = 49 pixels in the 7×7
  // window, equal weights) and Var (the pixel alone), and its mean over the interior must match the spread of the
  // prefiltered albedo about 0.5 within a factor 1.5 (measured: 1.05). The formula reads the weights as fixed while
  // NL-means weights depend on the noise; and the spread is a mean of correlated values (neighbours share most of
  // their window: about 42²/49 · 3 ≈ 100 independent ones), whose own relative standard error is about 15 %: 1.5 is
  // 3 of those. Without the update the variance stays 10⁻³, about 50 times the spread.
  constexpr int kSize = 48, kRadius = 3;
  constexpr double kVariance = 1e-3;
  DenoiseInput in = synthetic(kSize, kSize, 0.1, [](int, int) { return 1.0; }, [](int, int) { return 0.5; }, 9);
  std::mt19937 rng(10);
  std::normal_distribution<double> noise(0.0, std::sqrt(kVariance));
  for (float& a : in.albedo) a += float(noise(rng));
  in.albedo_variance.assign(in.albedo_variance.size(), float(kVariance));
  PreparedDenoiseInput d = prepare_denoise_input(in);
  prefilter_features(d, kRadius, 1.0);
  double spread = 0.0, reported = 0.0;
  int count = 0;
  for (int y = kRadius; y < kSize - kRadius; ++y)
    for (int x = kRadius; x < kSize - kRadius; ++x) {
      const size_t p = size_t(y) * kSize + size_t(x);
      const double v = d.feature_variance[0][p];
      CHECK(v <= kVariance * (1 + 1e-6));
      CHECK(v >= kVariance / 49.0 * (1 - 1e-6));
      for (int k = 0; k < 3; ++k) spread += (d.features[p * kDenoiseFeatures + size_t(k)] - 0.5) * (d.features[p * kDenoiseFeatures + size_t(k)] - 0.5);
      reported += v;
      ++count;
    }
  spread /= 3.0 * count;
  reported /= count;
  CAPTURE(spread);
  CAPTURE(reported);
  CHECK(spread / reported < 1.5);
  CHECK(spread / reported > 1.0 / 1.5);
}

TEST_CASE("denoise: candidates are chosen by relative error, so a dim channel counts as much as a bright one") {
  // One pixel, channel 0 bright (100), channel 1 dim (1), channel 2 at 10; both halves exact. Candidate A is off by
  // 1 on the bright channel (1 %), candidate B by 0.5 on the dim one (50 %). An absolute error prefers B (0.25 < 1);
  // the relative one A, and keeps preferring it when a channel's unit changes (channel 0 × 1000).
  for (const double scale : {1.0, 1000.0}) {
    DenoiseInput in = synthetic(1, 1, 0.0, [](int, int) { return 0.0; }, [](int, int) { return 0.5; }, 11);
    const float truth[3] = {float(100 * scale), 1.0f, 10.0f};
    for (auto& half : in.halves) std::copy(truth, truth + 3, half.begin());
    const PreparedDenoiseInput d = prepare_denoise_input(in);
    FilteredHalves filtered(2);
    for (auto& half : filtered[0]) half = {float(101 * scale), 1.0f, 10.0f};
    for (auto& half : filtered[1]) half = {float(100 * scale), 1.5f, 10.0f};
    const std::vector<std::vector<float>> error = candidate_errors(d, filtered);
    CAPTURE(scale);
    CAPTURE(error[0][0]);
    CAPTURE(error[1][0]);
    CHECK(error[0][0] < error[1][0]);
    // (1/101)² (the scale is the first candidate's estimate, 101) averaged over 3 channels; the halves agree.
    CHECK(error[0][0] == doctest::Approx(1.0 / (101.0 * 101.0) / 3.0).epsilon(1e-5));
  }
}

TEST_CASE("denoise: NaN and infinite inputs give a finite image") {
  constexpr int kSize = 32;
  DenoiseInput in = synthetic(kSize, kSize, 0.1, [](int, int) { return 1.0; }, [](int, int) { return 0.5; }, 6);
  const float bad[] = {NAN, INFINITY, -INFINITY};
  for (size_t i = 0; i < 3; ++i) {
    const size_t p = 37 * (i + 1);
    in.halves[i % 2][3 * p] = bad[i];
    in.variance[p + 1] = bad[i];
    in.albedo[3 * (p + 2)] = bad[i];
    in.normal[3 * (p + 3) + 1] = bad[i];
    in.depth[p + 4] = bad[i];
    in.albedo_variance[p + 5] = bad[i];
    in.normal_variance[p + 6] = bad[i];
    in.depth_variance[p + 7] = bad[i];
  }
  const DenoiseResult out = denoise(in);
  for (float v : out.image) CHECK(std::isfinite(v));
}

TEST_CASE("denoise: rimu denoise refuses a file that is no EXR or lacks the feature layers, writing nothing") {
  const fs::path dir = fs::temp_directory_path() / "rimu_denoise_test";
  fs::create_directories(dir);
  const fs::path not_exr = dir / "not.exr", out = dir / "out.exr";
  std::ofstream(not_exr) << "not an image";
  fs::remove(out);
  std::ostringstream log;
  CHECK_THROWS_WITH_AS(denoise_exr_file(not_exr, out, {}, log), doctest::Contains("not.exr"), InputError);
  CHECK_FALSE(fs::exists(out));
  CHECK_THROWS_WITH_AS(denoise_exr_file(dir / "missing.exr", out, {}, log), doctest::Contains("missing.exr"), InputError);
  CHECK_FALSE(fs::exists(out));
  CHECK_THROWS_WITH_AS(denoise_exr_file(not_exr, not_exr, {}, log), doctest::Contains("another file"), InputError);
}
