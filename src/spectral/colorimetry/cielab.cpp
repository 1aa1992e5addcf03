#include "spectral/colorimetry/cielab.h"

#include <cmath>
#include <numbers>

namespace rimu {

namespace {

/// CIE 15:2004 section 8.2.1: f(t) = t^(1/3) above ε, else the tangent-matched line (κ·t + 16)/116.
/// At t = ε both branches equal 6/29 and both slopes equal (1/3)(29/6)², so f is C¹.
double lab_f(double t) { return t > kCielabEpsilon ? std::cbrt(t) : (kCielabKappa * t + 16.0) / 116.0; }

/// The inverse of lab_f: f⁻¹(f) = f³ above 6/29, else (116 f − 16)/κ.
double lab_f_inverse(double f) {
  constexpr double kSwitch = 6.0 / 29.0;
  return f > kSwitch ? f * f * f : (116.0 * f - 16.0) / kCielabKappa;
}

/// L* from the relative luminance Y/Yn: 116 f(Y/Yn) − 16, which is κ·Y/Yn below ε. The linear branch is
/// evaluated directly: going through f would cancel the 16s and leave an absolute error of ulp(16) ≈ 4e-15 in
/// L*, a large relative error for very dark colours.
double lightness_of(double relative_y) {
  return relative_y > kCielabEpsilon ? 116.0 * std::cbrt(relative_y) - 16.0 : kCielabKappa * relative_y;
}

/// Y/Yn from L*: ((L*+16)/116)³ above L* = κε = 8, else L*/κ (again without the cancelling detour).
double relative_y_of(double lightness) {
  if (lightness > kCielabKappa * kCielabEpsilon) {
    const double f = (lightness + 16.0) / 116.0;
    return f * f * f;
  }
  return lightness / kCielabKappa;
}

}  // namespace

double hue_angle_deg(double y, double x) {
  if (x == 0.0 && y == 0.0) return 0.0;
  double h = std::atan2(y, x) * (180.0 / std::numbers::pi);
  if (h < 0.0) h += 360.0;
  // A hue a hair below 0° (atan2(-1e-300, 1)) rounds to exactly 360 after the shift; fold it back to 0.
  return h >= 360.0 ? h - 360.0 : h;
}

Lab lab_of(const Xyz& xyz, const Xyz& white) {
  const double fx = lab_f(xyz.x / white.x);
  const double fy = lab_f(xyz.y / white.y);
  const double fz = lab_f(xyz.z / white.z);
  // CIE 15:2004 section 8.2.1: L* = 116 f(Y/Yn) − 16, a* = 500 [f(X/Xn) − f(Y/Yn)], b* = 200 [f(Y/Yn) − f(Z/Zn)].
  return {lightness_of(xyz.y / white.y), 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Xyz xyz_from_lab(const Lab& lab, const Xyz& white) {
  const double fy = (lab.l + 16.0) / 116.0;
  const double fx = fy + lab.a / 500.0;
  const double fz = fy - lab.b / 200.0;
  return {white.x * lab_f_inverse(fx), white.y * relative_y_of(lab.l), white.z * lab_f_inverse(fz)};
}

Luv luv_of(const Xyz& xyz, const Xyz& white) {
  // CIE 15:2004 section 8.2.2: u* = 13 L* (u' − u'n), v* = 13 L* (v' − v'n). uv1976_of returns (0,0) for black,
  // where L* = 0 anyway, so black maps to (0,0,0) without a division by zero.
  const double lightness = lightness_of(xyz.y / white.y);
  const Uv1976 uv = uv1976_of(xyz);
  const Uv1976 uv_white = uv1976_of(white);
  return {lightness, 13.0 * lightness * (uv.u - uv_white.u), 13.0 * lightness * (uv.v - uv_white.v)};
}

Xyz xyz_from_luv(const Luv& luv, const Xyz& white) {
  if (luv.l == 0.0) return {};
  const Uv1976 uv_white = uv1976_of(white);
  const double u_prime = luv.u / (13.0 * luv.l) + uv_white.u;
  const double v_prime = luv.v / (13.0 * luv.l) + uv_white.v;
  const double y = white.y * relative_y_of(luv.l);
  // Invert u' = 4X/(X+15Y+3Z), v' = 9Y/(X+15Y+3Z): X = 9Y u'/(4v'), Z = Y (12 − 3u' − 20v')/(4v').
  return {y * 9.0 * u_prime / (4.0 * v_prime), y, y * (12.0 - 3.0 * u_prime - 20.0 * v_prime) / (4.0 * v_prime)};
}

Lch lch_of(const Lab& lab) { return {lab.l, std::hypot(lab.a, lab.b), hue_angle_deg(lab.b, lab.a)}; }

Lab lab_from_lch(const Lch& lch) {
  const double h_rad = lch.h_deg * (std::numbers::pi / 180.0);
  return {lch.l, lch.c * std::cos(h_rad), lch.c * std::sin(h_rad)};
}

Lch lch_of(const Luv& luv) { return {luv.l, std::hypot(luv.u, luv.v), hue_angle_deg(luv.v, luv.u)}; }

Luv luv_from_lch(const Lch& lch) {
  const double h_rad = lch.h_deg * (std::numbers::pi / 180.0);
  return {lch.l, lch.c * std::cos(h_rad), lch.c * std::sin(h_rad)};
}

}  // namespace rimu
