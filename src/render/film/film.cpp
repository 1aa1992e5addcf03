#include "render/film/film.h"

#include <cmath>
#include <string>

#include "spectral/error.h"

namespace rimu {
namespace {

PixelBounds checked_crop(const FilmOptions& o) {
  if (o.width <= 0 || o.height <= 0)
    throw InputError({"", 0, "--resolution"}, "the film needs a positive size; got " + std::to_string(o.width) +
                                                  "x" + std::to_string(o.height));
  if (o.spectral_bins < 0)
    throw InputError({"", 0, "--film"}, "the number of spectral bins cannot be negative");
  const PixelBounds whole{0, 0, o.width, o.height};
  if (!o.crop) return whole;
  const PixelBounds& c = *o.crop;
  if (c.empty() || c.intersect(whole) != c)
    throw InputError({"", 0, "--crop"}, "crop window " + std::to_string(c.x0) + "," + std::to_string(c.y0) + "," +
                                            std::to_string(c.x1) + "," + std::to_string(c.y1) +
                                            " must be non-empty and inside the " + std::to_string(o.width) + "x" +
                                            std::to_string(o.height) + " image (x0,y0,x1,y1, end exclusive)");
  return c;
}

}  // namespace

Film::Film(const FilmOptions& options, SpectralResponse response, std::vector<std::string> light_groups)
    : width_(options.width),
      height_(options.height),
      response_(std::move(response)),
      light_groups_(std::move(light_groups)),
      pixels_(checked_crop(options), response_, SpectralBinning{options.spectral_bins}, int(light_groups_.size())) {}

FilmTile Film::make_tile(const PixelBounds& bounds) const {
  FilmTile tile(bounds.intersect(pixel_bounds()), response_, binning(), int(light_groups_.size()));
  tile.set_max_channel_value(max_channel_value());
  return tile;
}

float Film::max_channel_value() const {
  if (!max_sample_value_) return INFINITY;
  const double threshold = *max_sample_value_ / output_.scale;
  return threshold > 0.0 && std::isfinite(threshold) ? float(threshold) : INFINITY;
}

void Film::merge_tile(const FilmTile& tile) {
  const PixelBounds& b = tile.bounds();
  const int n = pixels_.doubles_per_pixel();
  for (int y = b.y0; y < b.y1; ++y) {
    for (int x = b.x0; x < b.x1; ++x) {
      const double* from = tile.pixel(x, y);
      double* to = pixels_.pixel(x, y);
      for (int i = 0; i < n; ++i) to[i] += from[i];
    }
  }
  const FilmSampleCounts& c = tile.sample_counts();
  accepted_.fetch_add(c.accepted, std::memory_order_relaxed);
  nan_.fetch_add(c.nan, std::memory_order_relaxed);
  infinite_.fetch_add(c.infinite, std::memory_order_relaxed);
  negative_.fetch_add(c.negative, std::memory_order_relaxed);
  clamped_.fetch_add(c.clamped, std::memory_order_relaxed);
}

void Film::add_sample(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda,
                      float filter_weight, const SampledSpectrum* group_radiance) {
  pixels_.add_sample(x, y, radiance, lambda, filter_weight, group_radiance);
}

void Film::add_splat(int x, int y, const SampledSpectrum& radiance, const SampledWavelengths& lambda, float weight,
                     const SampledSpectrum* group_radiance) {
  pixels_.add_splat(x, y, radiance, lambda, weight, group_radiance);
}

std::array<double, 3> Film::group_value(int x, int y, int group) const {
  const double* p = pixels_.pixel(x, y);
  const double w = p[FilmTile::kWeight];
  if (w == 0.0) return {0.0, 0.0, 0.0};
  const double* g = p + pixels_.first_group_sum() + pixels_.group_stride() * group;
  return {g[0] / w, g[1] / w, g[2] / w};
}

double Film::group_spectral_value(int x, int y, int group, int bin) const {
  const double* p = pixels_.pixel(x, y);
  const double w = p[FilmTile::kWeight];
  return w == 0.0 ? 0.0 : p[pixels_.first_group_sum() + pixels_.group_stride() * group + 3 + bin] / w;
}

std::array<double, 3> Film::pixel_value(int x, int y) const {
  const double* p = pixels_.pixel(x, y);
  const double w = p[FilmTile::kWeight];
  if (w == 0.0) return {0.0, 0.0, 0.0};
  return {p[0] / w, p[1] / w, p[2] / w};
}

double Film::spectral_value(int x, int y, int bin) const {
  const double* p = pixels_.pixel(x, y);
  const double w = p[FilmTile::kWeight];
  return w == 0.0 ? 0.0 : p[FilmTile::kFirstBin + bin] / w;
}

FilmSampleCounts Film::sample_counts() const {
  FilmSampleCounts c = pixels_.sample_counts();  // from add_sample
  c += FilmSampleCounts{accepted_.load(), nan_.load(), infinite_.load(), negative_.load(), clamped_.load()};
  return c;
}

}  // namespace rimu
