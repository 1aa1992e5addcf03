// Error of a rendered XYZ image against a reference: the figures of the speed-against-error report (issue 7).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "render/film/film.h"
#include "spectral/colorimetry/chromaticity.h"

namespace rimu {

/// A film's pixel values (the crop window, row by row), detached from the film.
struct XyzImage {
  int width = 0, height = 0;
  std::vector<Xyz> pixels;

  /// Copies the mean pixel values of `film`'s crop window.
  static XyzImage from_film(const Film& film);
  /// Raw binary file (width, height, then 3 doubles per pixel): the report's cache of converged references.
  void write_raw(const std::string& path) const;
  /// Reads a write_raw() file; false if it is missing or malformed.
  bool read_raw(const std::string& path);
};

/// How far `image` is from `reference` (same size).
struct ImageError {
  /// Mean over pixels and channels of (v − r)² / (r² + ε²), ε = 0.01 × the reference's mean Y (the ε keeps black
  /// pixels from dominating; relative MSE as used by e.g. Rousselle et al. 2011, with a denominator floor).
  double relative_mse = 0;
  /// √(mean over pixels and channels of (v − r)²), in film units.
  double rmse_xyz = 0;
  /// CIEDE2000 per pixel, both images in CIELAB under `white`: mean and 95th percentile.
  double mean_delta_e2000 = 0;
  double p95_delta_e2000 = 0;
};

/// The error of `image` against `reference`, CIELAB relative to `white` (whose Y sets the lightness scale).
ImageError image_error(const XyzImage& image, const XyzImage& reference, const Xyz& white);

/// The mean XYZ of `image` over each group of pixels (`groups[i]` = the group of pixel i, negative = none).
std::map<int, Xyz> group_means(const XyzImage& image, const std::vector<int>& groups);

/// The scene white for CIELAB: the chromaticity of `white_xyz` (any scale) at the luminance of the 95th-percentile
/// pixel Y of `reference` (the brightest surfaces, not the lights, which cover less than 5% of the report's views).
Xyz scene_white(const XyzImage& reference, const Xyz& white_xyz);

}  // namespace rimu
