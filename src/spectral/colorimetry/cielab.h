// CIE 1976 L*a*b* (CIELAB) and L*u*v* (CIELUV), and their cylindrical L*C*h forms (CIE 15:2004 section 8.2).
#pragma once

#include "spectral/colorimetry/chromaticity.h"

namespace rimu {

/// CIELAB coordinates. L* is 0 for black and 100 for the reference white.
struct Lab {
  double l = 0, a = 0, b = 0;
};

/// CIELUV coordinates.
struct Luv {
  double l = 0, u = 0, v = 0;
};

/// Cylindrical form of CIELAB or CIELUV: chroma C* and hue angle h in degrees, in [0, 360).
struct Lch {
  double l = 0, c = 0, h_deg = 0;
};

/// The CIE 15:2004 constants in exact rational form. CIE 15:2004 (section 8.2.1) switches f(t) from t^(1/3) to
/// (841/108)·t + 16/116 at t = (24/116)³; that threshold is exactly ε = 216/24389 = (6/29)³, and the linear
/// branch gives L* = κ·Y/Yn with κ = 116·841/108 = 24389/27 = (29/3)³. The rounded 0.008856 and 903.3 of older
/// texts make L* jump by 3.3e-5 at the switch (7.99962 vs 7.99959); the exact fractions make f and its slope
/// continuous there.
inline constexpr double kCielabEpsilon = 216.0 / 24389.0;
inline constexpr double kCielabKappa = 24389.0 / 27.0;

/// CIELAB of `xyz` relative to `reference_white` (same scale: both Y = 1 or both Y = 100). Black gives (0,0,0).
Lab lab_of(const Xyz& xyz, const Xyz& reference_white);
/// The inverse of lab_of.
Xyz xyz_from_lab(const Lab& lab, const Xyz& reference_white);

/// CIELUV of `xyz` relative to `reference_white` (CIE 15:2004 section 8.2.2). Black gives (0,0,0).
Luv luv_of(const Xyz& xyz, const Xyz& reference_white);
/// The inverse of luv_of; L* = 0 gives black.
Xyz xyz_from_luv(const Luv& luv, const Xyz& reference_white);

/// C*ab = √(a*² + b*²), h_ab = atan2(b*, a*) in degrees [0, 360); the hue of a neutral (a* = b* = 0) is 0.
Lch lch_of(const Lab& lab);
Lab lab_from_lch(const Lch& lch);
/// C*uv and h_uv, the same construction on (u*, v*).
Lch lch_of(const Luv& luv);
Luv luv_from_lch(const Lch& lch);

/// Hue angle atan2(y, x) in degrees mapped into [0, 360), with atan2(0, 0) = 0.
double hue_angle_deg(double y, double x);

}  // namespace rimu
