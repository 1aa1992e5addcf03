#include "transport/guiding/path_guiding_record.h"

#include <array>
#include <cmath>

#include "transport/sampling/equal_area_square.h"

namespace rimu {
namespace {

// A Gaussian with different widths left and right of its mean (the lobe shape of Wyman et al. 2013).
float piecewise_gaussian(float x, float mean, float sigma_left, float sigma_right) {
  const float t = (x - mean) / (x < mean ? sigma_left : sigma_right);
  return std::exp(-0.5f * t * t);
}

float y_bar_fit(float lambda_nm) {
  return 0.821f * piecewise_gaussian(lambda_nm, 568.8f, 46.9f, 40.5f) +
         0.286f * piecewise_gaussian(lambda_nm, 530.9f, 16.3f, 31.1f);
}

}  // namespace

Float4 guiding_lane_weights(const SampledWavelengths& lambda, bool rgb) {
  if (rgb) return Float4(0.2126f, 0.7152f, 0.0722f, 0.0f);
  const auto pdf = lambda.pdf().to_array();
  std::array<float, kLaneCount> w{};
  for (int j = 0; j < kLaneCount; ++j)
    w[size_t(j)] = pdf[size_t(j)] > 0.0f ? y_bar_fit(lambda.lambda_nm(j)) / (float(kLaneCount) * pdf[size_t(j)]) : 0.0f;
  return Float4::load(w.data());
}

bool PathGuidingRecord::add_vertex(Vec3 position, int facing, Vec3 direction, float pdf, float cosine,
                                   const SampledSpectrum& throughput) {
  if (count_ == kMaxVertices) return false;
  if (count_ > 0) vertices_[size_t(count_ - 1)].open = false;
  Vertex& v = vertices_[size_t(count_++)];
  v.position = position;
  v.facing = facing;
  v.square = equal_area_sphere_to_square(direction);
  v.cosine_over_pdf = pdf > 0.0f ? cosine / pdf : 0.0f;
  v.inverse_throughput = select(throughput != Float4(0.0f), Float4(1.0f) / throughput, Float4(0.0f));
  v.incident = SampledSpectrum(0.0f);
  v.distance = 0.0f;
  v.open = true;
  return true;
}

void PathGuidingRecord::add_radiance(const SampledSpectrum& contribution, bool skip_last) {
  for (int i = 0, n = count_ - (skip_last ? 1 : 0); i < n; ++i) vertices_[size_t(i)].incident += contribution * vertices_[size_t(i)].inverse_throughput;
}

void PathGuidingRecord::flush(std::vector<GuidingSample>& out) const {
  for (int i = 0; i < count_; ++i) {
    const Vertex& v = vertices_[size_t(i)];
    const float luminance = sum(lane_weights_ * v.incident);
    // Negative lanes (never expected) or rounding: the field learns only non-negative, finite weights.
    const float weight = luminance > 0.0f ? luminance * v.cosine_over_pdf : 0.0f;
    out.push_back({v.position, {v.square, std::isfinite(weight) ? weight : 0.0f}, v.facing,
                   v.distance > 0.0f ? v.distance : INFINITY});
  }
}

}  // namespace rimu
