// The representation of upsampled spectra: values on 5 nm knots over 360-830 nm, linear in between, and the
// linear map from those knot values to XYZ under a colour space's white.
#pragma once

#include <array>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colorimetry/observer.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

/// 360, 365, ..., 830 nm: the observer's whole range (wavelength_range.h) in 5 nm steps.
inline constexpr int kUpsampleKnotCount = 95;
inline constexpr double kUpsampleFirstKnotNm = 360.0;
inline constexpr double kUpsampleKnotSpacingNm = 5.0;

/// Wavelength of knot `i` in nm.
constexpr double upsample_knot_nm(int i) { return kUpsampleFirstKnotNm + kUpsampleKnotSpacingNm * i; }

/// A spectrum's values at the knots (double precision: setup and table generation).
using KnotValues = std::array<double, kUpsampleKnotCount>;

/// XYZ of knot spectra, seen as reflectances under one white illuminant.
///
/// A knot spectrum is S(λ) = Σ S_i h_i(λ) with h_i the 10 nm wide "hat" around knot i, so its tristimulus values
/// are linear in the knots: X = Σ S_i a_i^X with a_i^X = Σ_λ h_i(λ) W(λ) x̄(λ) Δλ / Σ_λ W(λ) ȳ(λ) Δλ, summed on
/// the CIE 15 1 nm grid over 360-830 nm (the same sum colorimetry.h's reflectance_xyz makes). So Y of the
/// perfect diffuser is 1.
///
/// The white: a colour space's white chromaticity is a rounded number (D65 = 0.3127, 0.3290), while the CIE
/// table's D65 sums to (0.31272, 0.32903). The X and Z rows are therefore rescaled (by 1 + O(1e-4)) so that the
/// flat spectrum 1 maps exactly onto the space's white XYZ. That makes RGB (1,1,1) upsample to exactly 1 and an
/// upsampled reflectance lit by this white reproduce the input RGB through the space's own matrix.
class KnotColorimetry {
 public:
  /// Builds the rows for `illuminant` (relative power) and `observer`, matched to the space white `white`.
  KnotColorimetry(const Observer& observer, const Spectrum& illuminant, Chromaticity white);

  /// XYZ (perfect diffuser Y = 1) of the knot spectrum `knots`.
  Xyz xyz_of(const KnotValues& knots) const;
  /// Row k (0 = X, 1 = Y, 2 = Z): the weights a_i.
  const KnotValues& row(int k) const { return rows_[k]; }
  /// Chromaticity of knot i's hat alone: the saturated colours a knot spectrum can reach are their convex hull.
  Chromaticity knot_chromaticity(int i) const;
  Chromaticity white() const { return white_; }
  /// The space white with Y = 1 (what the flat spectrum 1 maps to).
  Xyz white_xyz() const { return white_xyz_; }
  /// The factors the X and Z rows were multiplied by (1 ± ~1e-4): how far the illuminant's own white is from
  /// the space's rounded white.
  double x_row_scale() const { return x_row_scale_; }
  double z_row_scale() const { return z_row_scale_; }

 private:
  std::array<KnotValues, 3> rows_{};
  Chromaticity white_;
  Xyz white_xyz_;
  double x_row_scale_ = 1, z_row_scale_ = 1;
};

}  // namespace rimu
