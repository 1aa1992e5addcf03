#include "render/denoise/denoise_film.h"

#include <cmath>

#include "render/denoise/denoise_layers.h"
#include "render/output/aov_channels.h"

namespace rimu {

DenoisedFilm denoise_film(const Film& film, const FeatureBuffers& features, const DenoiseSettings& settings) {
  const PixelBounds& b = film.pixel_bounds();
  const std::array<std::string, 3>& names = film.response().channel_names();
  const auto layers = aov_channels(features, film, AovSelection::all());
  const DenoiseInput input = denoise_input_from_layers(
      b.width(), b.height(), names,
      [&](const std::string& name) -> const std::vector<float>* {
        for (const auto& [n, v] : layers)
          if (n == name) return &v;
        return nullptr;
      },
      "the render");
  const DenoiseResult result = denoise(input, settings);

  DenoisedFilm out;
  out.seconds = result.seconds;
  for (int k = 0; k < 3; ++k) out.noisy_layer.emplace_back("noisy." + names[size_t(k)], std::vector<float>());
  FilmOptions options{film.width(), film.height(), b, film.binning().count};
  out.film = std::make_unique<Film>(options, film.response(), film.light_groups());
  out.film->set_output_transform(film.output_transform());
  const FilmOutputTransform& t = film.output_transform();
  const Matrix3 to_film = t.channel_matrix.inverse();
  FilmTile tile = out.film->make_tile(b);
  size_t i = 0;
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x, ++i) {
      const std::array<double, 3> noisy = film.output_value(x, y);
      for (int k = 0; k < 3; ++k)
        out.noisy_layer[size_t(k)].second.push_back(std::isfinite(noisy[size_t(k)]) ? float(noisy[size_t(k)]) : 0.0f);
      const double* from = film.accumulators(x, y);
      double* to = tile.pixel(x, y);
      for (int a = 0; a < film.accumulators_per_pixel(); ++a) to[a] = from[a];
      const double weight = from[FilmTile::kWeight];
      std::array<double, 3> denoised{};
      for (int k = 0; k < 3; ++k) denoised[size_t(k)] = double(result.image[3 * i + size_t(k)]) / t.scale;
      const std::array<double, 3> film_units = to_film.apply(denoised);
      for (int k = 0; k < 3; ++k) to[k] = weight > 0.0 && std::isfinite(film_units[size_t(k)]) ? film_units[size_t(k)] * weight : 0.0;
    }
  tile.add_sample_counts(film.sample_counts());
  out.film->merge_tile(tile);
  return out;
}

}  // namespace rimu
