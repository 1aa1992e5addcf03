// An intensity distribution stored as a square image in the equal-area octahedral mapping (equal_area_square.h):
// pbrt-v4's goniometric light. The value towards a direction is that of the pixel the direction falls in (pbrt's
// nearest-pixel lookup), so I is piecewise constant over pixels that each subtend 4π/N² sr.
//
// Integral: ∫ I dω = (4π/N²) Σ pixels, exactly. Sampling: a pixel with probability ∝ its value, then a point uniform
// in it, mapped to the sphere; the map preserves area, so p(ω) = p(u, v)/4π = I(ω)/∫I exactly.
#pragma once

#include <vector>

#include "transport/sampling/distribution_2d.h"
#include "transport/lights/intensity_distribution.h"

namespace rimu {

class EqualAreaIntensity final : public IntensityDistribution {
 public:
  /// `values`: `resolution`² finite values ≥ 0 (asserted: the scene loader checks the image), row by row from the
  /// image's top row, as pbrt-v4 indexes its images.
  EqualAreaIntensity(int resolution, std::vector<double> values);

  double intensity(Vec3 w) const override;
  double integral_sr() const override { return integral_; }
  double peak() const override { return peak_; }
  std::optional<DirectionSample> sample(Vec2 u) const override;
  float pdf(Vec3 w) const override;
  /// The whole sphere when any pixel is non-zero (no tighter cone is computed).
  std::optional<std::pair<double, double>> nonzero_gamma_rad() const override;

  int resolution() const { return resolution_; }
  double pixel(int x, int y) const { return values_[size_t(y) * size_t(resolution_) + size_t(x)]; }

 private:
  /// The pixel (x, y) local direction `w` falls in.
  std::pair<int, int> pixel_of(Vec3 w) const;

  int resolution_;
  std::vector<double> values_;
  Distribution2D pixels_;
  double integral_ = 0.0, peak_ = 0.0;
};

}  // namespace rimu
