// The denoiser (render/denoise/nfor_denoiser.h) on synthetic images whose answer is known: a constant under Gaussian
// noise with flat features loses most of its error, an edge the albedo shows stays sharp, a noiseless image is left
// alone; and `rimu denoise` refuses files it cannot denoise without writing anything.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "render/denoise/denoise_exr.h"
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
  const DenoiseSettings settings;  // window radius 7: 225 pixels
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
  // between two bandwidths and the regression's ridge terms cost a little more. The bound is N/2 (measured: 152); a filter that
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
