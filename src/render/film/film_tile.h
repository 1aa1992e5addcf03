// One thread's share of the film: the pixel accumulators of a rectangle, filled without locks.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "render/film/spectral_response.h"
#include "spectral/wavelengths/sampled_wavelengths.h"

namespace rimu {

/// A half-open pixel rectangle [x0, x1) × [y0, y1) in full-image coordinates (y down, as in EXR).
struct PixelBounds {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  int64_t area() const { return int64_t(width()) * height(); }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  /// The overlap of two rectangles (empty if they do not meet).
  PixelBounds intersect(const PixelBounds& o) const;
  friend bool operator==(const PixelBounds&, const PixelBounds&) = default;
};

/// A crop given as fractions of the image, [x0, x1) × [y0, y1) in [0, 1] (y down): pbrt's "cropwindow", which
/// keeps selecting the same part of the picture at any resolution. Its pixels at width × height are pbrt-v4's,
/// ⌈width·x0⌉ ≤ x < ⌈width·x1⌉ (likewise y).
struct CropWindow {
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;

  PixelBounds pixels(int width, int height) const {
    return {int(std::ceil(width * x0)), int(std::ceil(height * y0)), int(std::ceil(width * x1)),
            int(std::ceil(height * y1))};
  }
  friend bool operator==(const CropWindow&, const CropWindow&) = default;
};

/// N equal bins over 360-830 nm for the optional spectral framebuffer.
struct SpectralBinning {
  int count = 0;  ///< 0 = no spectral framebuffer
  double bin_width_nm() const;
  double bin_start_nm(int bin) const;
  double bin_centre_nm(int bin) const;
};

/// How many samples were accepted, and how many were discarded for which reason. A discarded sample is never
/// written to any pixel. Reasons are checked in this order (a sample is counted once): NaN anywhere in a live
/// lane (radiance or pdf), then ±Inf (including L/p overflowing), then negative radiance or pdf.
/// Negative radiance is a bug upstream (radiance and BSDFs are non-negative), so it is counted on its own
/// rather than clamped: clamping would hide the bug and bias the image.
struct FilmSampleCounts {
  uint64_t accepted = 0;
  uint64_t nan = 0;
  uint64_t infinite = 0;
  uint64_t negative = 0;
  /// Accepted samples scaled down by the film's sample clamp (FilmTile::set_max_channel_value): counted among
  /// `accepted`, not discarded.
  uint64_t clamped = 0;

  uint64_t discarded() const { return nan + infinite + negative; }
  FilmSampleCounts& operator+=(const FilmSampleCounts& o);
};

/// Pixel accumulators for one rectangle: per pixel the filter-weighted sums of the three channel values,
/// the sum of filter weights (= the sample count with importance-sampled positive filters, weight 1), and the
/// optional spectral bins. Sums are doubles: a render adds thousands of samples per pixel.
///
/// Thread model: a tile is owned by one thread at a time; nothing in it is shared, so add_sample needs no lock.
/// Film::merge_tile adds the tile's sums into the film.
class FilmTile {
 public:
  /// An empty tile over `bounds` (pixels outside the film's crop window must not be given samples), with
  /// `light_groups` layers besides the beauty (0: a scene without light groups), each of three channel sums and, on a
  /// spectral film, its own binning.count bin sums.
  FilmTile(PixelBounds bounds, const SpectralResponse& response, SpectralBinning binning, int light_groups = 0);

  /// Adds one camera sample to pixel (x, y) (full-image coordinates inside bounds()).
  ///
  /// `radiance` lane j must be an unbiased estimate of L(λ_j) on its own; the film averages the lanes:
  ///   value_k = (1/4) Σ_{j: p_j ≠ 0} L_j c_k(λ_j) / p_j,   p_j = lambda.pdf()[j].
  /// (In docs/transport.md's notation the integrator passes 4·β_j/Σ_k R_k, which is β_j when nothing depends on λ;
  /// after terminate_secondary() the hero's pdf is p/4 and it passes the single-wavelength estimate.)
  /// Lanes with p_j = 0 are skipped whatever their radiance. Spectral bin b (width Δ) receives
  ///   (1/4) Σ_j L_j 1[λ_j ∈ b] / (p_j Δ),
  /// whose expectation is the mean of L over the bin. A sample with NaN/Inf/negative values is discarded and
  /// counted (FilmSampleCounts), never written. Cost: a few dozen SSE instructions plus N-bin writes.
  /// With a sample clamp (set_max_channel_value), a sample whose largest channel value exceeds it is scaled down
  /// to it, its bins and light groups by the same factor, and counted as clamped.
  /// `group_radiance` (light_group_count() values, required when the tile has light groups, ignored otherwise):
  /// each group's share of `radiance`, accumulated by the same estimator into the group's three channel sums and
  /// spectral bins. A discarded sample is discarded from every layer, so the layers keep summing to the beauty.
  void add_sample(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda,
                  float filter_weight = 1.0f, const SampledSpectrum* group_radiance = nullptr);
  /// A light-traced contribution (caustic light tracing, transport/integrators/caustic_light_tracer.h): added to the
  /// pixel's sums as a sample of filter weight `weight` would be (sample clamp, bins and groups alike), without
  /// adding to its weight sum or its accepted count: the pixel's camera samples, which the sums are divided by, also
  /// count the light paths traced with them. Non-finite or negative values are discarded and counted.
  void add_splat(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda, float weight,
                 const SampledSpectrum* group_radiance = nullptr);

  /// The sample clamp: a sample's channel values (before the filter weight) are scaled so that the largest is at
  /// most `value` (film units, > 0; infinity: no clamp, the default). Biased: it trades rare bright samples'
  /// variance for a darker mean (docs/rendering.md, "Sample clamp").
  void set_max_channel_value(float value) { max_channel_value_ = value; }
  float max_channel_value() const { return max_channel_value_; }

  const PixelBounds& bounds() const { return bounds_; }
  const SpectralBinning& binning() const { return binning_; }
  const FilmSampleCounts& sample_counts() const { return counts_; }
  /// Adds counts of samples taken elsewhere (a partial render read back from its file, whose sums are loaded with
  /// pixel()).
  void add_sample_counts(const FilmSampleCounts& counts) { counts_ += counts; }
  int light_group_count() const { return light_groups_; }
  /// Accumulators per pixel: 3 channel sums, the weight sum, the N spectral bin sums, then per group its 3 channel
  /// sums and its N bin sums: 4 + N + G·(3 + N).
  int doubles_per_pixel() const { return first_group_sum() + group_stride() * light_groups_; }
  /// The index of light group 0's first channel sum among a pixel's accumulators (group g at + group_stride()·g,
  /// its bins after its 3 channel sums).
  int first_group_sum() const { return kFirstBin + binning_.count; }
  /// Accumulators per light group: 3 channel sums and the spectral bins.
  int group_stride() const { return 3 + binning_.count; }
  /// The accumulators of pixel (x, y), full-image coordinates.
  const double* pixel(int x, int y) const { return &data_[offset(x, y)]; }
  double* pixel(int x, int y) { return &data_[offset(x, y)]; }
  /// Zeroes every accumulator and count (a tile object can be reused for the next rectangle of the same size).
  void clear();

  static constexpr int kWeight = 3;
  static constexpr int kFirstBin = 4;

 private:
  void accumulate(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda, float filter_weight,
                  bool splat, const SampledSpectrum* group_radiance);
  size_t offset(int x, int y) const {
    return (size_t(y - bounds_.y0) * size_t(bounds_.width()) + size_t(x - bounds_.x0)) * size_t(doubles_per_pixel());
  }

  PixelBounds bounds_;
  const SpectralResponse* response_;
  SpectralBinning binning_;
  int light_groups_ = 0;
  std::vector<double> data_;
  FilmSampleCounts counts_;
  float max_channel_value_ = INFINITY;
};

}  // namespace rimu
