#include "render/denoise/denoise_selection.h"

#include <algorithm>
#include <limits>

namespace rimu {

std::vector<std::vector<float>> candidate_errors(const PreparedDenoiseInput& d, const FilteredHalves& filtered) {
  const size_t n = size_t(d.width) * size_t(d.height);
  std::vector<std::vector<float>> error(filtered.size(), std::vector<float>(n, 0.0f));
  for (size_t p = 0; p < n; ++p)
    for (int ch = 0; ch < 3; ++ch) {
      // The channel's scale: the first candidate's estimate squared, plus a half's variance so that a channel near 0
      // (or negative, out of gamut in the film's space) is not divided by ~0.
      const size_t i = 3 * p + size_t(ch);
      const double m = 0.5 * (double(filtered[0][0][i]) + filtered[0][1][i]);
      const double inverse_scale = 1.0 / (m * m + double(d.half_variance[p]) + 1e-30);
      for (size_t c = 0; c < filtered.size(); ++c)
        for (int t = 0; t < 2; ++t) {
          const double diff = double(filtered[c][size_t(t)][i]) - d.halves[size_t(1 - t)][i];
          const double e = double(error[c][p]) + diff * diff * inverse_scale / 6.0;
          error[c][p] = float(std::min(e, double(std::numeric_limits<float>::max())));
        }
    }
  return error;
}

}  // namespace rimu
