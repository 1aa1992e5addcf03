// The CIE standard general sky: the relative luminance distributions of ISO 15469:2004 / CIE S 011/E:2003
// ("Spatial distribution of daylight – CIE standard general sky"), 15 sky types from heavy overcast to turbid clear.
//
// A sky element at zenith angle Z whose angular distance from the sun is χ has, relative to the zenith,
//   L(χ, Z) / L_z = f(χ) φ(Z) / (f(Z_s) φ(0))                                           (CIE S 011 eq. 1)
// with the gradation function (luminance versus height, φ(90°) = 1 at the horizon)
//   φ(Z) = 1 + a exp(b / cos Z)    (Z < 90°; the limit 1 at Z = 90° since b < 0)      (eq. 2)
// and the scattering indicatrix (luminance versus distance from the sun)
//   f(χ) = 1 + c [exp(d χ) − exp(d π/2)] + e cos² χ                                    (eq. 3)
// where cos χ = cos Z_s cos Z + sin Z_s sin Z cos|α − α_s| (α azimuth, Z_s and α_s the sun's). The zenith's
// distance from the sun is Z_s, hence f(Z_s) in the denominator.
//
// The parameters (CIE S 011/E:2003 Table 1; also Darula & Kittler, "CIE general sky standard defining luminance
// distributions", eSim 2002): six gradation groups I-VI (a, b) and six indicatrix groups 1-6 (c, d, e); each
// sky type is one pair. Type 1 is the CIE standard overcast sky's modern form: its horizon is 1/φ(0) = 0.3349 of
// the zenith (the traditional Moon & Spencer overcast sky, (1 + 2 sin h)/3, has 1/3 there but is up to 20 %
// brighter just above the horizon). Type 5 is the uniform sky,
// types 12 and 13 the CIE standard clear sky (clean and polluted air).
//
// The formula is defined for the sun at or above the horizon (Z_s ≤ 90°) and for sky elements above it (Z < 90°).
#pragma once

#include <array>

namespace rimu {

/// The five parameters of one sky type.
struct CieSkyParameters {
  double a, b;     ///< gradation
  double c, d, e;  ///< indicatrix
  int gradation_group;   ///< I-VI as 1-6
  int indicatrix_group;  ///< 1-6
};

inline constexpr int kCieSkyTypeCount = 15;

/// The parameters of sky type `type` in 1-15 (asserted).
const CieSkyParameters& cie_sky_parameters(int type);
/// The standard's one-line description of sky type `type` in 1-15, e.g. "CIE standard overcast sky, ...".
const char* cie_sky_description(int type);

/// φ(Z) for cos Z = `cos_zenith` in [0, 1]; 1 at the horizon (cos Z = 0).
double cie_gradation(const CieSkyParameters& p, double cos_zenith);
/// f(χ) for χ = `chi_rad` in [0, π].
double cie_indicatrix(const CieSkyParameters& p, double chi_rad);

/// L/L_z of sky type `p` at a sky element of zenith angle `zenith_rad` ∈ [0, π/2] whose azimuth differs from the
/// sun's by `azimuth_from_sun_rad`, with the sun at zenith angle `sun_zenith_rad` ∈ [0, π/2]. Evaluated in double
/// exactly as eq. 1-3 above.
double cie_relative_luminance(const CieSkyParameters& p, double zenith_rad, double azimuth_from_sun_rad,
                              double sun_zenith_rad);

/// The same from unit vectors in a frame whose +z is the zenith: `element` (z ≥ 0) and `sun` (z ≥ 0). 0 below the
/// horizon (element.z ≤ 0).
double cie_relative_luminance(const CieSkyParameters& p, const std::array<double, 3>& element,
                              const std::array<double, 3>& sun);

/// One sky type with the sun fixed: eq. 1 with its denominator f(Z_s) φ(0) computed once (the sky light evaluates
/// it per sample and integrates it over millions of points at load). Same results as the functions above.
class CieSkyLuminance {
 public:
  /// `sun` a unit vector with +z the zenith (z ≥ 0 for the standard's range).
  CieSkyLuminance(const CieSkyParameters& p, const std::array<double, 3>& sun);
  /// L/L_z towards unit `element` (+z zenith); 0 below the horizon (element.z ≤ 0).
  double operator()(const std::array<double, 3>& element) const;
  const CieSkyParameters& parameters() const { return p_; }
  const std::array<double, 3>& sun() const { return sun_; }

 private:
  CieSkyParameters p_;
  std::array<double, 3> sun_;
  double exp_d_half_pi_;    // exp(d π/2)
  double inverse_zenith_;   // 1 / (f(Z_s) φ(0))
};

}  // namespace rimu
