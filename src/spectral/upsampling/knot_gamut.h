// The chromaticities a non-negative knot spectrum can have, and a polar coordinate system over them.
#pragma once

#include <vector>

#include "spectral/upsampling/upsampling_knots.h"

namespace rimu {

/// The convex hull of the knots' chromaticities under one white: every non-negative knot spectrum lies inside
/// it (its XYZ is a non-negative mix of the hats' XYZ), and every point inside is reached by some mix. It is the
/// discrete stand-in for the spectral locus and the purple line; it lies inside the true locus by the blur of a
/// 10 nm hat (≤ 0.004 in xy along the green edge, less elsewhere).
///
/// Points are addressed in polar form around the white: an angle θ (radians, atan2(y − y_w, x − x_w)) and a
/// relative radius ρ = |xy − white| / R(θ), where R(θ) is the distance from the white to the hull edge along θ.
/// ρ = 0 is the white, ρ = 1 the hull boundary, ρ > 1 outside.
class KnotGamut {
 public:
  /// The hull of `colorimetry`'s knot chromaticities around its white.
  explicit KnotGamut(const KnotColorimetry& colorimetry);
  /// A hull given by its vertices (counter-clockwise) around `white`; for tables read from disk.
  KnotGamut(Chromaticity white, std::vector<Chromaticity> vertices);

  /// R(θ): distance in xy from the white to the hull edge along the ray at `angle_rad`.
  double boundary_radius(double angle_rad) const;
  /// ρ of `xy` (see above); 0 at the white.
  double relative_radius(Chromaticity xy) const;
  /// The chromaticity at polar coordinates (angle, ρ).
  Chromaticity at(double angle_rad, double relative_radius) const;

  Chromaticity white() const { return white_; }
  const std::vector<Chromaticity>& vertices() const { return vertices_; }

 private:
  Chromaticity white_;
  std::vector<Chromaticity> vertices_;  // counter-clockwise, white strictly inside
};

}  // namespace rimu
