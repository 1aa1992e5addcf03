// A luminous (or radiant) intensity distribution I(γ, C) over the sphere, tabulated as in a goniometric
// measurement (IES LM-63 type C): γ is the angle from the light's axis (0 = nadir for a downlight), C the angle
// around it (0-360°). Values are interpolated bilinearly in (γ, C), so they are exact at the grid points.
//
// Directions are local: (sin γ cos C, sin γ sin C, cos γ). Outside the tabulated γ range the intensity is 0 (a
// table over 0-90° is dark above the horizon). The C grid must run from 0 to 360° (the IES reader expands the
// format's symmetries into a full turn before building this).
//
// Integral. Over a cell [γ0, γ1] × [C0, C1] the bilinear interpolant integrates exactly to
//   ΔC · [ (I00 + I01)/2 · (A − B) + (I10 + I11)/2 · B ],  A = cos γ0 − cos γ1,
//   B = ∫ t sin γ dγ = (sin γ1 − sin γ0)/Δγ − cos γ1,  t = (γ − γ0)/Δγ,
// (I0· at γ0, I1· at γ1, each averaged over the cell's two C edges since the interpolant is linear in C); the sum
// over cells is the total ∫ I dω (lm for candela).
//
// Sampling. A Distribution2D over the cells with weights (mean of the four corners) × (solid angle ΔC·A) picks a
// cell; inside it, C is uniform and cos γ uniform, i.e. uniform in solid angle. So p(ω) = P(cell)/Ω_cell: a
// piecewise-constant approximation of I/∫I, exact in the limit of fine tables and never 0 where I > 0.
#pragma once

#include <optional>
#include <vector>

#include "transport/sampling/distribution_2d.h"
#include "transport/lights/intensity_distribution.h"
#include "transport/geometry/vector.h"

namespace rimu {

class CandelaDistribution final : public IntensityDistribution {
 public:
  /// `gamma_deg` strictly increasing in [0, 180] (≥ 2 values), `c_deg` strictly increasing from 0 to 360 (≥ 2
  /// values), `values[c_index · gamma_count + gamma_index]` ≥ 0 (asserted: the IES reader checks user input).
  CandelaDistribution(std::vector<double> gamma_deg, std::vector<double> c_deg, std::vector<double> values);

  /// I at local direction `w` (unit), bilinear between grid points.
  double intensity(Vec3 w) const override;
  /// I at angles γ, C in degrees (C taken modulo 360).
  double intensity_deg(double gamma_deg, double c_deg) const;
  /// ∫ I dω over the sphere (exact for the bilinear interpolant): lm for a candela table.
  double integral_sr() const override { return integral_; }
  /// The largest tabulated value.
  double peak() const override { return peak_; }

  /// A direction with density ≈ I(w)/∫I (see above); std::nullopt if the table is all zero. Cost O(log n).
  std::optional<DirectionSample> sample(Vec2 u) const override;
  /// The solid-angle density sample() has at local direction `w`.
  float pdf(Vec3 w) const override;

  /// The γ range of the non-zero grid values widened to the neighbouring grid angles the bilinear interpolation
  /// reaches.
  std::optional<std::pair<double, double>> nonzero_gamma_rad() const override;
  const std::vector<double>& gamma_deg() const { return gamma_deg_; }
  const std::vector<double>& c_deg() const { return c_deg_; }

 private:
  double value(size_t c_index, size_t gamma_index) const { return values_[c_index * gamma_deg_.size() + gamma_index]; }

  std::vector<double> gamma_deg_, c_deg_, values_;
  std::vector<double> cos_gamma_;  // per grid γ
  Distribution2D cells_;           // width: C cells, height: γ cells
  double integral_ = 0, peak_ = 0;
};

}  // namespace rimu
