// The per-pixel feature buffers a denoiser reads (`rimu --aov`, `--denoise`): the beauty split into two half buffers,
// its variance, and the first non-specular hit's albedo, normal and depth with their variances.
#pragma once

#include <array>
#include <vector>

#include "render/film/film_tile.h"
#include "transport/integrators/path_features.h"

namespace rimu {

/// One camera sample's share of the feature buffers, the beauty's part read from the film tile it went to.
struct FeatureSample {
  int half = 0;                              ///< 0: an even sample index, 1: an odd one
  std::array<double, 3> beauty_sum{};        ///< what the sample added to the film's three channel sums
  double beauty_weight = 0.0;                ///< and to its weight sum (0: the film discarded the sample)
  std::array<double, 3> albedo{};            ///< the albedo in the film's channels (feature_albedo_channels)
  Vec3 normal{};
  double depth = 0.0;
};

/// The albedo of `features` in the film's three channels: per channel k, Σ_j a_j c_k(λ_j)/p_j / Σ_j c_k(λ_j)/p_j
/// over the sample's live lanes j, the lanes' albedos weighted by how much the channel sees each wavelength. Exact
/// (and noiseless) for a grey surface, between the lanes' smallest and largest albedo always; the plain lane mean
/// when the channel sees none of the four wavelengths. Cheap: one response evaluation, which the film does anyway.
std::array<double, 3> feature_albedo_channels(const PathFeatures& features, const SampledWavelengths& lambda,
                                              const SpectralResponse& response);

/// Accumulators over a rectangle of pixels, laid out as the film's tiles are: filled by one thread, then merged.
///
/// Per pixel: for each half (even, odd sample indices) the beauty's three channel sums and weight sum; the sums of
/// each sample's squared channel values (times its weight); the sums of albedo (3), normal (3) and depth; the sums
/// of their squares (albedo and normal summed over their components); and the count of feature samples.
class FeatureTile {
 public:
  FeatureTile() = default;
  explicit FeatureTile(PixelBounds bounds);
  const PixelBounds& bounds() const { return bounds_; }
  /// Adds one camera sample to pixel (x, y). A sample the film discarded (beauty_weight 0) adds no features either.
  void add(int x, int y, const FeatureSample& sample);
  const double* pixel(int x, int y) const { return &data_[offset(x, y)]; }
  double* pixel(int x, int y) { return &data_[offset(x, y)]; }

  static constexpr int kHalf0 = 0, kHalf1 = 4, kSquares = 8, kAlbedo = 11, kNormal = 14, kDepth = 17,
                       kAlbedoSquares = 18, kNormalSquares = 19, kDepthSquares = 20, kCount = 21, kPerPixel = 22;

 private:
  size_t offset(int x, int y) const {
    return (size_t(y - bounds_.y0) * size_t(bounds_.width()) + size_t(x - bounds_.x0)) * size_t(kPerPixel);
  }
  PixelBounds bounds_;
  std::vector<double> data_;
};

/// The feature buffers of a whole film (its crop window). Values are in film units, before the film's output
/// transform; every accessor returns finite values (0 for a pixel without samples).
class FeatureBuffers {
 public:
  explicit FeatureBuffers(PixelBounds bounds) : pixels_(bounds) {}
  const PixelBounds& pixel_bounds() const { return pixels_.bounds(); }
  FeatureTile make_tile(const PixelBounds& bounds) const { return FeatureTile(bounds.intersect(pixel_bounds())); }
  /// Adds a tile's sums (tiles of one pass do not overlap, so merges may run concurrently).
  void merge_tile(const FeatureTile& tile);

  /// The mean of half `half`'s samples at (x, y), in film channels; 0 without samples.
  std::array<double, 3> half_value(int half, int x, int y) const;
  /// The per-channel variance of the beauty's mean at (x, y): the samples' variance over their count,
  ///   (Σw v² / W − m²) / (W − 1),
  /// 0 with fewer than two samples.
  std::array<double, 3> beauty_variance(int x, int y) const;
  std::array<double, 3> albedo(int x, int y) const;
  Vec3 normal(int x, int y) const;  ///< the mean normal (not renormalised: shorter where normals disagree)
  double depth(int x, int y) const;
  /// The variances of the features' means (albedo and normal: averaged over their components), as beauty_variance.
  double albedo_variance(int x, int y) const;
  double normal_variance(int x, int y) const;
  double depth_variance(int x, int y) const;

 private:
  double variance_of_mean(int x, int y, int sum, int squares, int components) const;
  FeatureTile pixels_;
};

}  // namespace rimu
