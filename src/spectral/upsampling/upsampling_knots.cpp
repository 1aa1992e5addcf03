#include "spectral/upsampling/upsampling_knots.h"

#include <cmath>

#include "spectral/colorimetry/colorimetry.h"

namespace rimu {

KnotColorimetry::KnotColorimetry(const Observer& observer, const Spectrum& illuminant, Chromaticity white)
    : white_(white), white_xyz_(xyz_from_xyY(white, 1.0)) {
  const IntegrationGrid grid = IntegrationGrid::cie_1nm();
  const double white_y = integrate_on_grid(grid, [&](double l) { return illuminant.value(l) * observer.y_bar.value(l); });
  const TabulatedSpectrum* cmf[3] = {&observer.x_bar, &observer.y_bar, &observer.z_bar};
  for (int i = 0; i < kUpsampleKnotCount; ++i) {
    const double knot_nm = upsample_knot_nm(i);
    auto hat = [&](double l) { return std::fmax(0.0, 1.0 - std::abs(l - knot_nm) / kUpsampleKnotSpacingNm); };
    for (int k = 0; k < 3; ++k)
      rows_[k][i] = integrate_on_grid(grid, [&](double l) { return hat(l) * illuminant.value(l) * cmf[k]->value(l); }) /
                    white_y;
  }
  // The hats sum to 1 on 360-830 nm, so Σ_i a_i^Y = 1 already; X and Z are matched to the space's white.
  double sums[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k)
    for (double a : rows_[k]) sums[k] += a;
  x_row_scale_ = white_xyz_.x / sums[0];
  z_row_scale_ = white_xyz_.z / sums[2];
  for (int i = 0; i < kUpsampleKnotCount; ++i) {
    rows_[0][i] *= x_row_scale_;
    rows_[1][i] /= sums[1];
    rows_[2][i] *= z_row_scale_;
  }
}

Xyz KnotColorimetry::xyz_of(const KnotValues& knots) const {
  Xyz out;
  for (int i = 0; i < kUpsampleKnotCount; ++i) {
    out.x += rows_[0][i] * knots[i];
    out.y += rows_[1][i] * knots[i];
    out.z += rows_[2][i] * knots[i];
  }
  return out;
}

Chromaticity KnotColorimetry::knot_chromaticity(int i) const {
  return chromaticity_of(Xyz{rows_[0][i], rows_[1][i], rows_[2][i]});
}

}  // namespace rimu
