// The film: the image plane's accumulated estimate of each pixel's response-weighted radiance.
#pragma once

#include <array>
#include <atomic>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "render/film/film_output_transform.h"
#include "render/film/film_tile.h"
#include "render/film/spectral_response.h"

namespace rimu {

/// The film's size and what it records.
struct FilmOptions {
  int width = 0, height = 0;          ///< full image, pixels
  std::optional<PixelBounds> crop;    ///< the pixels actually rendered and stored; the whole image if unset
  int spectral_bins = 0;              ///< N bins over 360-830 nm; 0 = no spectral framebuffer
};

/// Per pixel of the crop window, the sums of the samples' channel values (and spectral bins) and of their filter
/// weights; a pixel's value is the ratio (the sample mean, since importance-sampled positive filters give every
/// sample weight 1). Channels are defined by the SpectralResponse (CIE XYZ or camera RGB).
///
/// Parallel rendering (oneTBB over tiles): each task makes a FilmTile with make_tile(), fills it alone (no locks,
/// no shared cache lines), and hands it to merge_tile(). merge_tile() may run concurrently for tiles whose bounds
/// do not overlap: it writes only the tile's own pixels and adds the sample counts atomically.
///
/// Determinism: a pixel's sum is (its previous sum) + (the tile's sum, accumulated in the order the tile's owner
/// added samples). Two renders that cut the image into the same tiles and the same passes, and add each tile's
/// samples in the same order, give bit-identical films whatever the thread count and whatever order tiles finish in.
/// (Merging two tiles that cover the same pixel in the same pass would make the result order-dependent; renderers
/// must not do that.)
class Film {
 public:
  /// Throws InputError if the size is not positive, the crop window is empty or leaves the image, or bins < 0.
  /// `light_groups`: the scene's light groups (Scene::light_groups): one layer of channel sums (and, with spectral
  /// bins, bin sums) per name besides the beauty, each the share of the image its lights emitted; the layers sum to
  /// the beauty. Empty: no layers, no cost.
  Film(const FilmOptions& options, SpectralResponse response, std::vector<std::string> light_groups = {});
  Film(const Film&) = delete;
  Film& operator=(const Film&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  /// The crop window (the whole image when none was given): where pixels are stored.
  const PixelBounds& pixel_bounds() const { return pixels_.bounds(); }
  const SpectralResponse& response() const { return response_; }
  const SpectralBinning& binning() const { return pixels_.binning(); }

  /// An empty tile over `bounds` ∩ pixel_bounds(), to be filled by one thread and passed to merge_tile().
  FilmTile make_tile(const PixelBounds& bounds) const;
  /// Adds a tile's sums and counts. Safe concurrently with other merges of non-overlapping tiles.
  void merge_tile(const FilmTile& tile);
  /// Adds one sample directly (single-threaded use only; see FilmTile::add_sample for the estimator).
  void add_sample(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda,
                  float filter_weight = 1.0f, const SampledSpectrum* group_radiance = nullptr);
  /// Adds a light-traced contribution directly (single-threaded use only; see FilmTile::add_splat).
  void add_splat(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda, float weight,
                 const SampledSpectrum* group_radiance = nullptr);

  /// The light groups' names, in layer order (empty: the film has no group layers).
  const std::vector<std::string>& light_groups() const { return light_groups_; }
  /// Group `group`'s mean channel values at pixel (x, y), like pixel_value(); they sum over groups to pixel_value().
  std::array<double, 3> group_value(int x, int y, int group) const;
  /// The same through output_transform(), as written to the group's EXR layer.
  std::array<double, 3> group_output_value(int x, int y, int group) const {
    return output_.apply(group_value(x, y, group));
  }

  /// The mean channel values of pixel (x, y) (full-image coordinates inside pixel_bounds()); 0 without samples.
  std::array<double, 3> pixel_value(int x, int y) const;
  /// The value written to output files: output_transform() applied to pixel_value() (exposure, white balance).
  std::array<double, 3> output_value(int x, int y) const { return output_.apply(pixel_value(x, y)); }
  /// Sets the exposure and white balance applied when the film is written (identity by default).
  void set_output_transform(const FilmOutputTransform& transform) {
    output_ = transform;
    pixels_.set_max_channel_value(max_channel_value());  // the clamp is in the written units
  }
  const FilmOutputTransform& output_transform() const { return output_; }
  /// The range a sample clamp may take, wherever it is given (the scene's film, `--max-sample-value`, Python).
  static constexpr double kMinSampleClamp = 1e-30, kMaxSampleClamp = 1e30;
  static bool valid_sample_clamp(double value) { return value >= kMinSampleClamp && value <= kMaxSampleClamp; }
  /// The range in words, for messages ("1e-30 to 1e+30"), written from the two bounds above.
  static std::string sample_clamp_range() {
    char text[64];
    std::snprintf(text, sizeof text, "%g to %g", kMinSampleClamp, kMaxSampleClamp);
    return text;
  }
  /// The sample clamp (film "max_sample_value", `--max-sample-value`; docs/rendering.md, "Sample clamp"): each
  /// sample's channel values, times the output transform's exposure scale, are scaled down so that the largest is at
  /// most `value` (the written image's units before white balance, as pbrt-v4's "maxcomponentvalue"). Tiles made
  /// after this call apply it (make_tile), as does add_sample. nullopt: no clamp.
  void set_max_sample_value(std::optional<double> value) {
    max_sample_value_ = value;
    pixels_.set_max_channel_value(max_channel_value());
  }
  std::optional<double> max_sample_value() const { return max_sample_value_; }
  /// The mean spectral radiance (W/(m²·sr·nm) if the input was) estimated in bin `bin` of pixel (x, y).
  double spectral_value(int x, int y, int bin) const;
  /// Group `group`'s share of spectral_value(x, y, bin); they sum over groups to it.
  double group_spectral_value(int x, int y, int group, int bin) const;
  /// The sum of filter weights of pixel (x, y) (its sample count with weight-1 filters).
  double weight_sum(int x, int y) const { return pixels_.pixel(x, y)[FilmTile::kWeight]; }
  /// The raw accumulators of pixel (x, y) (FilmTile layout: 3 channel sums, the weight sum, the bin sums, the light
  /// groups' channel and bin sums): what a partial render writes so that merging partials is summation.
  const double* accumulators(int x, int y) const { return pixels_.pixel(x, y); }
  int accumulators_per_pixel() const { return pixels_.doubles_per_pixel(); }
  /// Accepted and discarded samples over everything merged or added so far.
  FilmSampleCounts sample_counts() const;

 private:
  int width_, height_;
  SpectralResponse response_;
  std::vector<std::string> light_groups_;
  FilmTile pixels_;  // the whole crop window, in the tile layout
  FilmOutputTransform output_;
  std::optional<double> max_sample_value_;
  std::atomic<uint64_t> accepted_{0}, nan_{0}, infinite_{0}, negative_{0}, clamped_{0};

  /// The clamp in film units (the tiles' threshold): max_sample_value / exposure scale, or infinity.
  float max_channel_value() const;
};

}  // namespace rimu
