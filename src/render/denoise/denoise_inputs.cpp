#include "render/denoise/denoise_inputs.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace rimu {
namespace {

constexpr int kFeatures = kDenoiseFeatures;

float finite(float v) { return std::isfinite(v) ? v : 0.0f; }

}  // namespace

PreparedDenoiseInput prepare_denoise_input(const DenoiseInput& in) {
  const size_t n = size_t(in.width) * size_t(in.height);
  PreparedDenoiseInput p{in.width, in.height, {}, {}, std::vector<float>(n * kFeatures), {}};
  for (int h = 0; h < 2; ++h) {
    p.halves[size_t(h)].resize(3 * n);
    for (size_t i = 0; i < 3 * n; ++i) p.halves[size_t(h)][i] = finite(in.halves[size_t(h)][i]);
  }
  p.half_variance.resize(n);
  for (size_t i = 0; i < n; ++i) p.half_variance[i] = 2.0f * std::max(0.0f, finite(in.variance[i]));
  // Depth in units of the image's largest depth, so that one threshold and one ridge fit every scene's scale.
  float max_depth = 0.0f;
  for (size_t i = 0; i < n; ++i) max_depth = std::max(max_depth, finite(in.depth[i]));
  const float depth_scale = max_depth > 0.0f ? 1.0f / max_depth : 1.0f;
  for (size_t i = 0; i < n; ++i) {
    float* f = &p.features[i * kFeatures];
    for (int k = 0; k < 3; ++k) {
      f[k] = finite(in.albedo[3 * i + size_t(k)]);
      f[3 + k] = finite(in.normal[3 * i + size_t(k)]);
    }
    f[6] = finite(in.depth[i]) * depth_scale;
  }
  for (auto& v : p.feature_variance) v.resize(n);
  for (size_t i = 0; i < n; ++i) {
    p.feature_variance[0][i] = std::max(0.0f, finite(in.albedo_variance[i]));
    p.feature_variance[1][i] = std::max(0.0f, finite(in.normal_variance[i]));
    p.feature_variance[2][i] = std::max(0.0f, finite(in.depth_variance[i])) * depth_scale * depth_scale;
  }
  return p;
}

void prefilter_features(PreparedDenoiseInput& p, int radius, double bandwidth) {
  if (radius <= 0) return;
  static constexpr int kFirst[3] = {0, 3, 6}, kCount[3] = {3, 3, 1};
  constexpr int kPatch = 1, kRows = 16;
  const int w = p.width, h = p.height;
  const double inverse_k_sq = 1.0 / (bandwidth * bandwidth);
  std::vector<float> out(p.features.size());
  std::array<std::vector<float>, 3> out_variance;
  for (auto& v : out_variance) v.resize(p.feature_variance[0].size());
  const int blocks = (h + kRows - 1) / kRows;
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks), [&](const tbb::blocked_range<int>& range) {
    for (int block = range.begin(); block != range.end(); ++block) {
      // As the colour filter does: per offset (dx, dy), each pixel's distance to its neighbour there, then the
      // patch's mean of it by a box over rows and columns (clipped at the image's edges): the patch distance
      // costs O(1) per pixel and offset instead of O(patch).
      const int y0 = block * kRows, y1 = std::min(h, y0 + kRows);
      const int ey0 = std::max(0, y0 - kPatch), ey1 = std::min(h, y1 + kPatch), erows = ey1 - ey0;
      const size_t block_pixels = size_t(y1 - y0) * size_t(w), extended = size_t(erows) * size_t(w);
      std::vector<double> sum(block_pixels * kFeatures, 0.0), weight_sum(block_pixels, 0.0);
      std::vector<double> variance_sum(block_pixels * 3, 0.0);  // Σ w² Var, per feature group
      std::vector<float> raw(3 * extended), row_box(3 * extended);
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          for (int y = ey0; y < ey1; ++y)
            for (int x = 0; x < w; ++x) {
              const size_t a = size_t(y) * size_t(w) + size_t(x);
              const size_t b = size_t(std::clamp(y + dy, 0, h - 1)) * size_t(w) + size_t(std::clamp(x + dx, 0, w - 1));
              const size_t at = size_t(y - ey0) * size_t(w) + size_t(x);
              for (int g = 0; g < 3; ++g) {
                double sq = 0.0;
                for (int k = kFirst[g]; k < kFirst[g] + kCount[g]; ++k) {
                  const double diff = double(p.features[a * kFeatures + size_t(k)]) - p.features[b * kFeatures + size_t(k)];
                  sq += diff * diff;
                }
                const double va = p.feature_variance[size_t(g)][a], vb = p.feature_variance[size_t(g)][b];
                raw[size_t(g) * extended + at] =
                    float((sq / kCount[g] - (va + std::min(va, vb))) / (1e-8 + (va + vb) / inverse_k_sq));
              }
            }
          for (int g = 0; g < 3; ++g)
            for (int y = 0; y < erows; ++y)
              for (int x = 0; x < w; ++x) {
                const int xa = std::max(0, x - kPatch), xb = std::min(w - 1, x + kPatch);
                double s = 0.0;
                for (int xx = xa; xx <= xb; ++xx) s += raw[size_t(g) * extended + size_t(y) * size_t(w) + size_t(xx)];
                row_box[size_t(g) * extended + size_t(y) * size_t(w) + size_t(x)] = float(s / (xb - xa + 1));
              }
          for (int y = y0; y < y1; ++y) {
            const int qy = y + dy;
            if (qy < 0 || qy >= h) continue;
            const int ya = std::max(ey0, y - kPatch), yb = std::min(ey1 - 1, y + kPatch);
            for (int x = 0; x < w; ++x) {
              const int qx = x + dx;
              if (qx < 0 || qx >= w) continue;
              double worst = 0.0;
              for (int g = 0; g < 3; ++g) {
                double s = 0.0;
                for (int yy = ya; yy <= yb; ++yy) s += row_box[size_t(g) * extended + size_t(yy - ey0) * size_t(w) + size_t(x)];
                worst = std::max(worst, s / (yb - ya + 1));
              }
              const double weight = std::exp(-worst);
              const size_t q = size_t(qy) * size_t(w) + size_t(qx), local = size_t(y - y0) * size_t(w) + size_t(x);
              for (int k = 0; k < kFeatures; ++k) sum[local * kFeatures + size_t(k)] += weight * p.features[q * kFeatures + size_t(k)];
              weight_sum[local] += weight;
              for (int g = 0; g < 3; ++g) variance_sum[local * 3 + size_t(g)] += weight * weight * p.feature_variance[size_t(g)][q];
            }
          }
        }
      // weight_sum ≥ 1: the pixel's own weight (offset 0: every distance ≤ 0) is 1.
      for (size_t local = 0; local < block_pixels; ++local) {
        const size_t i = size_t(y0) * size_t(w) + local;
        for (int k = 0; k < kFeatures; ++k) out[i * kFeatures + size_t(k)] = float(sum[local * kFeatures + size_t(k)] / weight_sum[local]);
        for (int g = 0; g < 3; ++g)
          out_variance[size_t(g)][i] = float(variance_sum[local * 3 + size_t(g)] / (weight_sum[local] * weight_sum[local]));
      }
    }
  });
  p.features = std::move(out);
  p.feature_variance = std::move(out_variance);
}

void clamp_to_noise(const PreparedDenoiseInput& d, double sigmas, std::vector<float>& image) {
  if (!(sigmas > 0.0)) return;
  const int w = d.width, h = d.height;
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = size_t(y) * size_t(w) + size_t(x);
        double around[9];
        int count = 0;
        for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
          for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx)
            around[count++] = 0.5 * d.half_variance[size_t(yy) * size_t(w) + size_t(xx)];  // the whole's variance
        std::nth_element(around, around + count / 2, around + count);
        for (int ch = 0; ch < 3; ++ch) {
          const double a = d.halves[0][3 * p + size_t(ch)], b = d.halves[1][3 * p + size_t(ch)];
          const double sigma = std::sqrt(std::max({0.5 * double(d.half_variance[p]), 0.25 * (a - b) * (a - b), around[count / 2]}));
          float& out = image[3 * p + size_t(ch)];
          out = float(std::clamp(double(out), 0.5 * (a + b) - sigmas * sigma, 0.5 * (a + b) + sigmas * sigma));
        }
      }
  });
}

}  // namespace rimu
