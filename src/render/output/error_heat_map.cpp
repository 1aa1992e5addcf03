#include "render/output/error_heat_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/output/plot_output.h"

namespace rimu {

FalseColourValues adaptive_error_values(const AdaptiveSampling& adaptive, const PixelBounds& bounds) {
  FalseColourValues image;
  image.width = bounds.width();
  image.height = bounds.height();
  image.quantity = FalseColourQuantity::relative_error;
  image.values.reserve(size_t(bounds.area()));
  for (int y = bounds.y0; y < bounds.y1; ++y)
    for (int x = bounds.x0; x < bounds.x1; ++x) {
      const double percent = 100.0 * double(adaptive.relative_error(x, y));
      image.values.push_back(std::isfinite(percent) ? percent : std::nan(""));
    }
  return image;
}

FalseColourRange adaptive_error_range(double noise_threshold) {
  // In %: a tenth of the threshold is 10 × the fraction. A threshold of 10 (1000 %, the largest accepted) would
  // meet the top: the top then moves to ten times the bottom.
  const double low = 10.0 * noise_threshold;
  return {low, std::max(100.0, 10.0 * low)};
}

void write_error_heat_map(const std::filesystem::path& png, const AdaptiveSampling& adaptive,
                          const PixelBounds& bounds) {
  const FalseColourValues image = adaptive_error_values(adaptive, bounds);
  char title[160];
  std::snprintf(title, sizeof title, "remaining error: threshold %.3g %%, %.1f %% of the pixels still sampled",
                100.0 * adaptive.settings().noise_threshold,
                100.0 * double(adaptive.active_count()) / double(std::max<long long>(bounds.area(), 1)));
  draw_plot_png(false_colour_job(image, adaptive_error_range(adaptive.settings().noise_threshold), title), png);
}

}  // namespace rimu
