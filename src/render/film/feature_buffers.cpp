#include "render/film/feature_buffers.h"

#include <algorithm>
#include <cmath>

namespace rimu {

std::array<double, 3> feature_albedo_channels(const PathFeatures& features, const SampledWavelengths& lambda,
                                              const SpectralResponse& response) {
  const Response4 c = response.evaluate(lambda);
  const Float4 pdf = lambda.pdf();
  const std::array<Float4, 3> channels{c.x, c.y, c.z};
  std::array<double, 3> out{};
  double lane_sum = 0.0;
  int live = 0;
  for (int j = 0; j < kLaneCount; ++j)
    if (pdf[j] > 0.0f) {
      lane_sum += features.albedo[j];
      ++live;
    }
  const double lane_mean = live > 0 ? lane_sum / live : 0.0;
  for (int k = 0; k < 3; ++k) {
    double weighted = 0.0, weights = 0.0;
    for (int j = 0; j < kLaneCount; ++j) {
      if (!(pdf[j] > 0.0f)) continue;
      const double w = std::fabs(double(channels[size_t(k)][j])) / double(pdf[j]);
      weighted += w * features.albedo[j];
      weights += w;
    }
    out[size_t(k)] = weights > 0.0 && std::isfinite(weighted / weights) ? weighted / weights : lane_mean;
  }
  return out;
}

FeatureTile::FeatureTile(PixelBounds bounds) : bounds_(bounds), data_(size_t(std::max<int64_t>(0, bounds.area())) * kPerPixel, 0.0) {}

void FeatureTile::add(int x, int y, const FeatureSample& s) {
  if (!(s.beauty_weight > 0.0)) return;
  double* p = pixel(x, y);
  double* half = p + (s.half == 0 ? kHalf0 : kHalf1);
  for (int k = 0; k < 3; ++k) {
    half[k] += s.beauty_sum[size_t(k)];
    // Σ w·v² with v = sum/w the sample's value.
    p[kSquares + k] += s.beauty_sum[size_t(k)] * s.beauty_sum[size_t(k)] / s.beauty_weight;
  }
  half[3] += s.beauty_weight;
  const double n[3] = {s.normal.x, s.normal.y, s.normal.z};
  for (int k = 0; k < 3; ++k) {
    p[kAlbedo + k] += s.albedo[size_t(k)];
    p[kAlbedoSquares] += s.albedo[size_t(k)] * s.albedo[size_t(k)];
    p[kNormal + k] += n[k];
    p[kNormalSquares] += n[k] * n[k];
  }
  p[kDepth] += s.depth;
  p[kDepthSquares] += s.depth * s.depth;
  p[kCount] += 1.0;
}

void FeatureBuffers::merge_tile(const FeatureTile& tile) {
  const PixelBounds& b = tile.bounds();
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x) {
      const double* from = tile.pixel(x, y);
      double* to = pixels_.pixel(x, y);
      for (int k = 0; k < FeatureTile::kPerPixel; ++k) to[k] += from[k];
    }
}

namespace {
double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }
}  // namespace

std::array<double, 3> FeatureBuffers::half_value(int half, int x, int y) const {
  const double* h = pixels_.pixel(x, y) + (half == 0 ? FeatureTile::kHalf0 : FeatureTile::kHalf1);
  if (!(h[3] > 0.0)) return {0.0, 0.0, 0.0};
  return {finite_or_zero(h[0] / h[3]), finite_or_zero(h[1] / h[3]), finite_or_zero(h[2] / h[3])};
}

std::array<double, 3> FeatureBuffers::beauty_variance(int x, int y) const {
  const double* p = pixels_.pixel(x, y);
  const double w = p[FeatureTile::kHalf0 + 3] + p[FeatureTile::kHalf1 + 3];
  std::array<double, 3> out{};
  if (!(w > 1.0)) return out;
  for (int k = 0; k < 3; ++k) {
    const double mean = (p[FeatureTile::kHalf0 + k] + p[FeatureTile::kHalf1 + k]) / w;
    out[size_t(k)] = finite_or_zero(std::max(0.0, p[FeatureTile::kSquares + k] / w - mean * mean) / (w - 1.0));
  }
  return out;
}

std::array<double, 3> FeatureBuffers::albedo(int x, int y) const {
  const double* p = pixels_.pixel(x, y);
  if (!(p[FeatureTile::kCount] > 0.0)) return {0.0, 0.0, 0.0};
  const double n = p[FeatureTile::kCount];
  return {finite_or_zero(p[FeatureTile::kAlbedo] / n), finite_or_zero(p[FeatureTile::kAlbedo + 1] / n),
          finite_or_zero(p[FeatureTile::kAlbedo + 2] / n)};
}

Vec3 FeatureBuffers::normal(int x, int y) const {
  const double* p = pixels_.pixel(x, y);
  if (!(p[FeatureTile::kCount] > 0.0)) return {};
  const double n = p[FeatureTile::kCount];
  return {float(finite_or_zero(p[FeatureTile::kNormal] / n)), float(finite_or_zero(p[FeatureTile::kNormal + 1] / n)),
          float(finite_or_zero(p[FeatureTile::kNormal + 2] / n))};
}

double FeatureBuffers::depth(int x, int y) const {
  const double* p = pixels_.pixel(x, y);
  return p[FeatureTile::kCount] > 0.0 ? finite_or_zero(p[FeatureTile::kDepth] / p[FeatureTile::kCount]) : 0.0;
}

double FeatureBuffers::variance_of_mean(int x, int y, int sum, int squares, int components) const {
  const double* p = pixels_.pixel(x, y);
  const double n = p[FeatureTile::kCount];
  if (!(n > 1.0)) return 0.0;
  double mean_squared = 0.0;
  for (int k = 0; k < components; ++k) mean_squared += (p[sum + k] / n) * (p[sum + k] / n);
  const double variance = std::max(0.0, p[squares] / n - mean_squared) / components;
  return finite_or_zero(variance / (n - 1.0));
}

double FeatureBuffers::albedo_variance(int x, int y) const {
  return variance_of_mean(x, y, FeatureTile::kAlbedo, FeatureTile::kAlbedoSquares, 3);
}
double FeatureBuffers::normal_variance(int x, int y) const {
  return variance_of_mean(x, y, FeatureTile::kNormal, FeatureTile::kNormalSquares, 3);
}
double FeatureBuffers::depth_variance(int x, int y) const {
  return variance_of_mean(x, y, FeatureTile::kDepth, FeatureTile::kDepthSquares, 1);
}

}  // namespace rimu
