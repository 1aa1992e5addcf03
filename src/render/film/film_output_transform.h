// What the film's written values are: the accumulated channels (film units) through one 3×3 channel matrix and one
// scale. This is the single place where the physical camera's exposure and white balance reach the output files
// (EXR and PNG both read Film::output_value()); the film's own sums, and the light meter that reads them, stay in
// film units.
#pragma once

#include <array>

#include "spectral/colour_spaces/matrix3.h"

namespace rimu {

/// v_out = scale · M · v_film. M is the white balance (identity without one), scale the exposure (1 without a
/// physical camera). Both are linear, so their order does not matter.
struct FilmOutputTransform {
  Matrix3 channel_matrix = Matrix3::identity();
  double scale = 1.0;

  /// The written value of a pixel whose film value is `film_value`.
  std::array<double, 3> apply(const std::array<double, 3>& film_value) const {
    std::array<double, 3> out = channel_matrix.apply(film_value);
    for (double& v : out) v *= scale;
    return out;
  }
};

}  // namespace rimu
