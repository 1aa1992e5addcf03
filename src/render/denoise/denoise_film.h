// `rimu --denoise`: the rendered film denoised from its feature buffers, as a film the EXR and PNG writers take.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/denoise/nfor_denoiser.h"
#include "render/film/feature_buffers.h"
#include "render/film/film.h"

namespace rimu {

struct DenoisedFilm {
  /// The same film (size, response, output transform, sample counts, light groups and spectral bins as rendered)
  /// with the beauty's channel sums replaced by the denoised values times each pixel's weight sum.
  std::unique_ptr<Film> film;
  /// The noisy beauty as written, "noisy.c0" … "noisy.c2" (ExrOptions::extra_channels).
  std::vector<std::pair<std::string, std::vector<float>>> noisy_layer;
  double seconds = 0.0;  ///< the denoiser's time
};

/// Denoises `film` with its `features`, in the written (output-transformed) values as `rimu denoise` reads them from
/// a file, and brings the result back to film units through the inverse of the output transform.
DenoisedFilm denoise_film(const Film& film, const FeatureBuffers& features, const DenoiseSettings& settings);

}  // namespace rimu
