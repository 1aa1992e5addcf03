// Tristimulus values of spectra, following CIE 15:2004 recommended practice.
#pragma once

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colorimetry/observer.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

/// The wavelengths a colorimetric sum runs over. CIE 15:2004 §7.1 recommends 360-830 nm at 1 nm and accepts
/// 380-780 nm at 5 nm (the "abridged" practice that the published tables, e.g. Table T.3, were computed with).
struct IntegrationGrid {
  double start_nm = 360.0;
  double end_nm = 830.0;
  double step_nm = 1.0;
  static IntegrationGrid cie_1nm() { return {360.0, 830.0, 1.0}; }
  static IntegrationGrid cie_5nm_abridged() { return {380.0, 780.0, 5.0}; }
};

/// Relative colorimetry of a light source: XYZ normalised so that Y = 100 (CIE 15:2004 eq. 7.1 with k = 100/Σ S ȳ Δλ).
Xyz illuminant_xyz(const Spectrum& illuminant, const Observer& observer,
                   IntegrationGrid grid = IntegrationGrid::cie_1nm());

/// A reflectance (or transmittance) factor seen under an illuminant: the perfect diffuser has Y = 100
/// (CIE 15:2004 eq. 7.2). Returns all zeros if the illuminant has no ȳ-weighted power.
Xyz reflectance_xyz(const Spectrum& reflectance, const Spectrum& illuminant, const Observer& observer,
                    IntegrationGrid grid = IntegrationGrid::cie_1nm());

/// Absolute colorimetry of an emission spectrum: X = K_m ∫ S x̄ dλ etc., with K_m = 683 lm/W. For a spectral
/// radiance in W/(m²·sr·nm) this gives Y in cd/m² (nits); for spectral power in W/nm, Y in lumens.
Xyz emission_xyz(const Spectrum& spectral_quantity, const Observer& observer,
                 IntegrationGrid grid = IntegrationGrid::cie_1nm());

/// Σ over the grid of f(λ)·Δλ: the rectangle rule CIE 15 uses (not the trapezoid: that changes the 5th decimal).
template <typename F>
double integrate_on_grid(const IntegrationGrid& grid, F&& f) {
  double sum = 0.0;
  const int count = int((grid.end_nm - grid.start_nm) / grid.step_nm + 0.5);
  for (int i = 0; i <= count; ++i) sum += f(grid.start_nm + i * grid.step_nm);
  return sum * grid.step_nm;
}

}  // namespace rimu
