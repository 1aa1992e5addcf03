#include "spectral/colorimetry/colorimetry.h"

#include "spectral/colorimetry/photometry_constants.h"

namespace rimu {
namespace {

Xyz weighted_xyz(const Spectrum& s, const Observer& o, const IntegrationGrid& grid) {
  return {integrate_on_grid(grid, [&](double l) { return s.value(l) * o.x_bar.value(l); }),
          integrate_on_grid(grid, [&](double l) { return s.value(l) * o.y_bar.value(l); }),
          integrate_on_grid(grid, [&](double l) { return s.value(l) * o.z_bar.value(l); })};
}

}  // namespace

Xyz illuminant_xyz(const Spectrum& illuminant, const Observer& observer, IntegrationGrid grid) {
  const Xyz raw = weighted_xyz(illuminant, observer, grid);
  if (raw.y == 0.0) return {};
  const double k = 100.0 / raw.y;
  return {k * raw.x, 100.0, k * raw.z};
}

Xyz reflectance_xyz(const Spectrum& reflectance, const Spectrum& illuminant, const Observer& observer,
                    IntegrationGrid grid) {
  const double white_y = integrate_on_grid(grid, [&](double l) { return illuminant.value(l) * observer.y_bar.value(l); });
  if (white_y == 0.0) return {};
  const double k = 100.0 / white_y;
  auto channel = [&](const TabulatedSpectrum& cmf) {
    return k * integrate_on_grid(grid, [&](double l) { return reflectance.value(l) * illuminant.value(l) * cmf.value(l); });
  };
  return {channel(observer.x_bar), channel(observer.y_bar), channel(observer.z_bar)};
}

Xyz emission_xyz(const Spectrum& spectral_quantity, const Observer& observer, IntegrationGrid grid) {
  const Xyz raw = weighted_xyz(spectral_quantity, observer, grid);
  return {kMaxLuminousEfficacy_lm_W * raw.x, kMaxLuminousEfficacy_lm_W * raw.y, kMaxLuminousEfficacy_lm_W * raw.z};
}

}  // namespace rimu
