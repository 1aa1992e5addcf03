#include "render/denoise/nfor_denoiser.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "render/denoise/denoise_inputs.h"
#include "render/denoise/denoise_selection.h"
#include "spectral/error.h"

namespace rimu {
namespace {

constexpr int kFeatures = kDenoiseFeatures;
using Prepared = PreparedDenoiseInput;
constexpr int kDesign = 1 + kFeatures;  // the intercept and the features' offsets from the centre pixel's
constexpr int kNormalTerms = kDesign * (kDesign + 1) / 2;
constexpr int kAccumulators = kNormalTerms + 3 * kDesign;
// Rousselle, Manzi & Zwicker 2013 ("Robust denoising using feature and color information"): a feature difference
// within this (in squared units of a feature normalised to about [0, 1]) is not an edge even where the feature is
// noiseless. 2e-3 rather than 1e-3 since the prefiltered features' variance is the small one left after the
// prefilter (docs/benchmarks.md, "Denoising").
constexpr double kFeatureThreshold = 2e-3;
// The ridge on the feature coefficients, relative to the weights' sum: a feature constant over the window then gets
// coefficient 0 (the fit falls back to the weighted mean) instead of an ill-posed system.
constexpr double kRidge = 1e-3;
constexpr int kRowsPerBlock = 4;
constexpr int kMaxCandidates = 16;  // colour × feature bandwidths
// A neighbour whose weight exp(−exponent) is below 1e-6 is skipped (and its exp not taken).
constexpr double kMaxExponent = 13.815510557964274;  // −ln 1e-6

float finite(float v) { return std::isfinite(v) ? v : 0.0f; }

// The feature distance of neighbour q to pixel p, whose weight at bandwidth k_f is exp(−distance / k_f²): the largest
// over the three features of their variance-cancelled squared distance, as Rousselle et al. 2013 weigh features
// (without their gradient term); at least 0.
double feature_distance(const Prepared& d, size_t p, size_t q) {
  static constexpr int kFirst[3] = {0, 3, 6}, kCount[3] = {3, 3, 1};
  double worst = 0.0;
  for (int g = 0; g < 3; ++g) {
    double sq = 0.0;
    for (int k = kFirst[g]; k < kFirst[g] + kCount[g]; ++k) {
      const double diff = double(d.features[p * kFeatures + size_t(k)]) - d.features[q * kFeatures + size_t(k)];
      sq += diff * diff;
    }
    sq /= kCount[g];
    const double vp = d.feature_variance[size_t(g)][p], vq = d.feature_variance[size_t(g)][q];
    const double distance = (sq - (vp + std::min(vp, vq))) / std::max(kFeatureThreshold, vp + vq);
    worst = std::max(worst, distance);
  }
  return worst;
}

// Solves the ridge-regularised weighted normal equations (A β = b, A symmetric, packed) by Cholesky and returns the
// intercept per channel; the weighted mean when the system is not positive definite or the fit is negative.
std::array<float, 3> solve_intercept(const double* acc) {
  const double weight_sum = acc[0];
  std::array<float, 3> mean{};
  if (!(weight_sum > 0.0)) return mean;
  const double* b = acc + kNormalTerms;
  for (int c = 0; c < 3; ++c) mean[size_t(c)] = float(b[c * kDesign] / weight_sum);
  double a[kDesign][kDesign];
  int t = 0;
  for (int i = 0; i < kDesign; ++i)
    for (int j = i; j < kDesign; ++j) a[i][j] = a[j][i] = acc[t++];
  for (int i = 1; i < kDesign; ++i) a[i][i] += kRidge * weight_sum;
  double l[kDesign][kDesign] = {};
  for (int j = 0; j < kDesign; ++j) {
    double s = a[j][j];
    for (int k = 0; k < j; ++k) s -= l[j][k] * l[j][k];
    if (!(s > 1e-12 * weight_sum)) return mean;
    l[j][j] = std::sqrt(s);
    for (int i = j + 1; i < kDesign; ++i) {
      double v = a[i][j];
      for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
      l[i][j] = v / l[j][j];
    }
  }
  std::array<float, 3> out{};
  for (int c = 0; c < 3; ++c) {
    double z[kDesign], x[kDesign];
    for (int i = 0; i < kDesign; ++i) {
      double v = b[c * kDesign + i];
      for (int k = 0; k < i; ++k) v -= l[i][k] * z[k];
      z[i] = v / l[i][i];
    }
    for (int i = kDesign - 1; i >= 0; --i) {
      double v = z[i];
      for (int k = i + 1; k < kDesign; ++k) v -= l[k][i] * x[k];
      x[i] = v / l[i][i];
    }
    // A negative intercept is extrapolation past what any neighbour shows (no colour is negative): keep the mean.
    if (!std::isfinite(x[0]) || x[0] < 0.0) return mean;
    out[size_t(c)] = float(x[0]);
  }
  return out;
}

}  // namespace

void check_denoise_input(const DenoiseInput& in, const std::string& where) {
  if (in.width <= 0 || in.height <= 0)
    throw InputError({where, 0, ""}, "the image to denoise is empty (" + std::to_string(in.width) + "x" +
                                         std::to_string(in.height) + ")");
  const size_t n = size_t(in.width) * size_t(in.height);
  const auto check = [&](const std::vector<float>& v, size_t channels, const char* name) {
    if (v.size() != n * channels)
      throw InputError({where, 0, name}, std::string("the denoiser's '") + name + "' buffer holds " +
                                             std::to_string(v.size()) + " values, not " + std::to_string(n * channels));
  };
  check(in.halves[0], 3, "half_even");
  check(in.halves[1], 3, "half_odd");
  check(in.variance, 1, "variance");
  check(in.albedo, 3, "albedo");
  check(in.normal, 3, "N");
  check(in.depth, 1, "depth.Z");
  check(in.albedo_variance, 1, "albedo_variance");
  check(in.normal_variance, 1, "N_variance");
  check(in.depth_variance, 1, "depth_variance");
}

namespace {

// One candidate filter: its colour and feature bandwidths.
struct Bandwidths {
  double colour, feature;
};

// `halves` = 1 filters half 0 only (the second pass, whose two halves are the same image).
FilteredHalves filter_halves(const Prepared& d, const DenoiseSettings& settings, const std::vector<Bandwidths>& bandwidths,
                             int halves = 2) {
  const int w = d.width, h = d.height, r = settings.window_radius, pr = settings.patch_radius;
  const size_t n = size_t(w) * size_t(h);
  const int candidates = int(bandwidths.size());
  std::vector<double> inverse_k_sq, inverse_feature_k_sq;
  for (const Bandwidths& k : bandwidths) {
    inverse_k_sq.push_back(1.0 / (k.colour * k.colour));
    inverse_feature_k_sq.push_back(1.0 / (k.feature * k.feature));
  }
  FilteredHalves filtered(static_cast<size_t>(candidates));
  for (auto& f : filtered)
    for (auto& half : f) half.assign(3 * n, 0.0f);

  const int blocks = (h + kRowsPerBlock - 1) / kRowsPerBlock;
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks), [&](const tbb::blocked_range<int>& range) {
    for (int block = range.begin(); block != range.end(); ++block) {
      const int y0 = block * kRowsPerBlock, y1 = std::min(h, y0 + kRowsPerBlock);
      // The patch distances need rows y0 − pr … y1 + pr.
      const int ey0 = std::max(0, y0 - pr), ey1 = std::min(h, y1 + pr), erows = ey1 - ey0;
      const size_t block_pixels = size_t(y1 - y0) * size_t(w);
      std::vector<double> acc(block_pixels * size_t(candidates) * 2 * kAccumulators, 0.0);
      std::array<std::vector<float>, 2> raw, row_box, patch;
      for (int g = 0; g < 2; ++g) {
        raw[size_t(g)].resize(size_t(erows) * size_t(w));
        row_box[size_t(g)].resize(size_t(erows) * size_t(w));
        patch[size_t(g)].resize(block_pixels);
      }
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          // Per guide half g: the variance-cancelled squared colour distance of each pixel to its neighbour at
          // (dx, dy) (Rousselle, Knaus & Zwicker 2012), neighbours outside the image clamped to its border.
          for (int y = ey0; y < ey1; ++y) {
            const int qy = std::clamp(y + dy, 0, h - 1);
            for (int x = 0; x < w; ++x) {
              const int qx = std::clamp(x + dx, 0, w - 1);
              const size_t p = size_t(y) * size_t(w) + size_t(x), q = size_t(qy) * size_t(w) + size_t(qx);
              const double vp = d.half_variance[p], vq = d.half_variance[q];
              const double cancel = vp + std::min(vp, vq), norm = 1e-10 + vp + vq;
              for (int g = 0; g < 2; ++g) {
                const float* c = d.halves[size_t(g)].data();
                double sq = 0.0;
                for (int k = 0; k < 3; ++k) {
                  const double diff = double(c[3 * p + size_t(k)]) - c[3 * q + size_t(k)];
                  sq += diff * diff;
                }
                raw[size_t(g)][size_t(y - ey0) * size_t(w) + size_t(x)] = float((sq / 3.0 - cancel) / norm);
              }
            }
          }
          // The patch mean: a box over (2pr + 1)² pixels, clipped at the image's edges.
          for (int g = 0; g < 2; ++g) {
            for (int y = 0; y < erows; ++y)
              for (int x = 0; x < w; ++x) {
                double s = 0.0;
                const int xa = std::max(0, x - pr), xb = std::min(w - 1, x + pr);
                for (int xx = xa; xx <= xb; ++xx) s += raw[size_t(g)][size_t(y) * size_t(w) + size_t(xx)];
                row_box[size_t(g)][size_t(y) * size_t(w) + size_t(x)] = float(s / (xb - xa + 1));
              }
            for (int y = y0; y < y1; ++y)
              for (int x = 0; x < w; ++x) {
                double s = 0.0;
                const int ya = std::max(ey0, y - pr), yb = std::min(ey1 - 1, y + pr);
                for (int yy = ya; yy <= yb; ++yy) s += row_box[size_t(g)][size_t(yy - ey0) * size_t(w) + size_t(x)];
                patch[size_t(g)][size_t(y - y0) * size_t(w) + size_t(x)] = float(s / (yb - ya + 1));
              }
          }
          for (int y = y0; y < y1; ++y) {
            const int qy = y + dy;
            if (qy < 0 || qy >= h) continue;
            for (int x = 0; x < w; ++x) {
              const int qx = x + dx;
              if (qx < 0 || qx >= w) continue;
              const size_t p = size_t(y) * size_t(w) + size_t(x), q = size_t(qy) * size_t(w) + size_t(qx);
              const size_t local = size_t(y - y0) * size_t(w) + size_t(x);
              const double feature_d = settings.feature_weights ? feature_distance(d, p, q) : 0.0;
              // The weight of each candidate and half; most neighbours of a pixel at an edge have none.
              double weights[kMaxCandidates][2];
              bool used[2] = {false, false};
              for (int c = 0; c < candidates; ++c)
                for (int t = 0; t < halves; ++t) {
                  // Half t is filtered with weights from the other half: the weights never see the noise they average.
                  const double dc = std::max(0.0, double(patch[size_t(1 - t)][local]) * inverse_k_sq[size_t(c)]);
                  const double exponent = std::max(dc, feature_d * inverse_feature_k_sq[size_t(c)]);
                  weights[c][t] = exponent > kMaxExponent ? 0.0 : std::exp(-exponent);  // below 1e-6: skipped
                  used[t] = used[t] || weights[c][t] > 0.0;
                }
              if (!used[0] && !used[1]) continue;
              double design[kDesign];
              design[0] = 1.0;
              for (int k = 0; k < kFeatures; ++k)
                design[1 + k] = double(d.features[q * kFeatures + size_t(k)]) - d.features[p * kFeatures + size_t(k)];
              // What neighbour q adds to the normal equations at weight 1, per half: the design's outer product
              // (packed upper triangle) and the colour times the design. Each candidate then adds it times its
              // weight, one contiguous multiply-add the compiler vectorises.
              alignas(16) double terms[kAccumulators];
              int term = 0;
              for (int i = 0; i < kDesign; ++i)
                for (int j = i; j < kDesign; ++j) terms[term++] = design[i] * design[j];
              for (int t = 0; t < halves; ++t) {
                if (!used[t]) continue;
                const float* colour = &d.halves[size_t(t)][3 * q];
                for (int ch = 0; ch < 3; ++ch)
                  for (int i = 0; i < kDesign; ++i) terms[kNormalTerms + ch * kDesign + i] = double(colour[ch]) * design[i];
                for (int c = 0; c < candidates; ++c) {
                  const double weight = weights[c][t];
                  if (weight == 0.0) continue;
                  double* a = &acc[((local * size_t(candidates) + size_t(c)) * 2 + size_t(t)) * kAccumulators];
                  for (int k = 0; k < kAccumulators; ++k) a[k] += weight * terms[k];
                }
              }
            }
          }
        }
      }
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t p = size_t(y) * size_t(w) + size_t(x), local = size_t(y - y0) * size_t(w) + size_t(x);
          for (int c = 0; c < candidates; ++c)
            for (int t = 0; t < halves; ++t) {
              const std::array<float, 3> v =
                  solve_intercept(&acc[((local * size_t(candidates) + size_t(c)) * 2 + size_t(t)) * kAccumulators]);
              for (int ch = 0; ch < 3; ++ch) filtered[size_t(c)][size_t(t)][3 * p + size_t(ch)] = v[size_t(ch)];
            }
        }
    }
  });
  return filtered;
}

}  // namespace

DenoiseResult denoise(const DenoiseInput& input, const DenoiseSettings& settings) {
  check_denoise_input(input, "denoiser input");
  const auto start = std::chrono::steady_clock::now();
  std::optional<tbb::global_control> thread_limit;
  if (settings.threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(settings.threads));

  Prepared d = prepare_denoise_input(input);
  prefilter_features(d, settings.feature_prefilter_radius, settings.feature_prefilter_bandwidth);
  const int w = d.width, h = d.height;
  const size_t n = size_t(w) * size_t(h);
  std::vector<Bandwidths> bandwidths;
  for (double colour : settings.colour_bandwidths)
    for (double feature : settings.feature_bandwidths) bandwidths.push_back({colour, feature});
  const int candidates = int(bandwidths.size());
  if (candidates < 1 || candidates > kMaxCandidates)
    throw InputError({"denoiser settings", 0, "colour_bandwidths"},
                     "the denoiser takes 1 to " + std::to_string(kMaxCandidates) + " candidate filters (colour × feature bandwidths), not " +
                         std::to_string(candidates));
  const FilteredHalves filtered = filter_halves(d, settings, bandwidths);

  const std::vector<std::vector<float>> error = candidate_errors(d, filtered);
  DenoiseResult result;
  result.image.assign(3 * n, 0.0f);
  result.chosen.assign(n, 0);
  const int sr = settings.selection_radius;
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < w; ++x) {
        int best = 0;
        double best_error = INFINITY;
        for (int c = 0; c < candidates; ++c) {
          double s = 0.0;
          for (int yy = std::max(0, y - sr); yy <= std::min(h - 1, y + sr); ++yy)
            for (int xx = std::max(0, x - sr); xx <= std::min(w - 1, x + sr); ++xx)
              s += error[size_t(c)][size_t(yy) * size_t(w) + size_t(xx)];
          if (s < best_error) {
            best_error = s;
            best = c;
          }
        }
        const size_t p = size_t(y) * size_t(w) + size_t(x);
        result.chosen[p] = best;
        for (int ch = 0; ch < 3; ++ch) {
          const float v = 0.5f * (filtered[size_t(best)][0][3 * p + size_t(ch)] + filtered[size_t(best)][1][3 * p + size_t(ch)]);
          const double a = d.halves[0][3 * p + size_t(ch)], b = d.halves[1][3 * p + size_t(ch)];
          double out = std::isfinite(v) ? v : 0.5 * (a + b);
          result.image[3 * p + size_t(ch)] = float(out);
        }
      }
  });
  if (settings.second_pass) {
    // Second pass: the mean of the two filtered halves filtered again, guided by itself, with the variance the
    // halves' difference shows.
    std::array<std::vector<float>, 2> selected{std::vector<float>(3 * n), std::vector<float>(3 * n)};
    for (size_t p = 0; p < n; ++p)
      for (int t = 0; t < 2; ++t)
        for (int ch = 0; ch < 3; ++ch)
          selected[size_t(t)][3 * p + size_t(ch)] = filtered[size_t(result.chosen[p])][size_t(t)][3 * p + size_t(ch)];
    Prepared second = d;
    for (size_t p = 0; p < n; ++p) {
      double v = 0.0;
      for (int ch = 0; ch < 3; ++ch) {
        const size_t i = 3 * p + size_t(ch);
        const double diff = finite(selected[0][i]) - finite(selected[1][i]);
        v += 0.25 * diff * diff / 3.0;
        second.halves[0][i] = second.halves[1][i] = result.image[i];
      }
      second.half_variance[p] = float(v);
    }
    const FilteredHalves again = filter_halves(second, settings, {{settings.second_pass_bandwidth, settings.feature_bandwidths.back()}}, 1);
    for (size_t i = 0; i < 3 * n; ++i) {
      const float v = again[0][0][i];
      if (std::isfinite(v)) result.image[i] = v;
    }
  }
  clamp_to_noise(d, settings.clamp_sigmas, result.image);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace rimu
