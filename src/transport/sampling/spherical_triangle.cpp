#include "transport/sampling/spherical_triangle.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rimu {
namespace {

struct Dvec {
  double x, y, z;
};
Dvec operator-(Dvec a, Dvec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Dvec operator+(Dvec a, Dvec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Dvec operator*(Dvec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Dvec a, Dvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Dvec cross(Dvec a, Dvec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(Dvec a) { return std::sqrt(dot(a, a)); }
Dvec normalized(Dvec a) { return a * (1.0 / length(a)); }

// The component of b perpendicular to the unit vector a: the great arc from a towards b leaves a along it.
Dvec tangent(Dvec a, Dvec b) { return b - a * dot(a, b); }

// The interior angle α at a between the arcs to b and to c, as atan2 of |t_b × t_c| and t_b · t_c (t the tangents
// at a); cos α and sin α from the same two numbers (|t_b × t_c|² + (t_b · t_c)² = |t_b|²|t_c|²), so no cos or sin
// of α is evaluated.
struct CornerAngle {
  double alpha = 0.0, cos_alpha = 1.0, sin_alpha = 0.0;
};
CornerAngle corner_angle(Dvec a, Dvec b, Dvec c) {
  const Dvec tb = tangent(a, b), tc = tangent(a, c);
  const double sine_part = length(cross(tb, tc)), cosine_part = dot(tb, tc);
  // Both parts are products of unit-length terms (≤ 1), so the plain root cannot overflow; std::hypot's care costs.
  const double h = std::sqrt(sine_part * sine_part + cosine_part * cosine_part);
  if (!(h > 0.0)) return {};
  return {std::atan2(sine_part, cosine_part), cosine_part / h, sine_part / h};
}

struct Corners {
  Dvec a, b, c;
  bool valid = false;
};

Corners corners_from(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2) {
  const auto relative = [&](Vec3 v) { return Dvec{double(v.x) - p.x, double(v.y) - p.y, double(v.z) - p.z}; };
  const Dvec d0 = relative(v0), d1 = relative(v1), d2 = relative(v2);
  const double l0 = length(d0), l1 = length(d1), l2 = length(d2);
  Corners out;
  if (!(l0 > 0.0 && l1 > 0.0 && l2 > 0.0) || !std::isfinite(l0 + l1 + l2)) return out;
  out.a = d0 * (1.0 / l0);
  out.b = d1 * (1.0 / l1);
  out.c = d2 * (1.0 / l2);
  out.valid = true;
  return out;
}

// Ω by Van Oosterom and Strackee (1983, IEEE Trans. Biomed. Eng. 30(2)): tan(Ω/2) = |a · (b × c)| / (1 + a·b +
// b·c + c·a) for unit corners, one atan2 where Girard's excess α + β + γ − π needs three. Both are exact; this one
// is also well conditioned for thin and far triangles (the triple product of unit vectors, in double). Girard's
// three atan2, evaluated twice per light sample, were 13 % of the Cornell box's CPU (docs/benchmarks.md, "Time to
// equal error, measured in CPU time"). 0 for a point in the triangle's plane.
double solid_angle(const Corners& k) {
  const double numerator = std::fabs(dot(k.a, cross(k.b, k.c)));
  const double denominator = 1.0 + dot(k.a, k.b) + dot(k.b, k.c) + dot(k.c, k.a);
  const double omega = 2.0 * std::atan2(numerator, denominator);
  return std::isfinite(omega) ? std::max(0.0, omega) : 0.0;
}

}  // namespace

double spherical_triangle_solid_angle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2) {
  const Corners k = corners_from(p, v0, v1, v2);
  return k.valid ? solid_angle(k) : 0.0;
}

std::optional<Vec3> sample_spherical_triangle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2, Vec2 u, double* solid_angle_sr) {
  const Corners k = corners_from(p, v0, v1, v2);
  if (!k.valid) return std::nullopt;
  const double omega = solid_angle(k);
  if (solid_angle_sr) *solid_angle_sr = omega;
  if (!(omega > 0.0)) return std::nullopt;
  const auto [alpha, cos_alpha, sin_alpha] = corner_angle(k.a, k.b, k.c);
  // The sub-triangle (a, b, ĉ) of area Â = u₁Ω: ĉ = q a + √(1 − q²) ĉ⊥, ĉ⊥ the unit tangent at a towards c, where
  // q = cos of the arc a–ĉ solves Girard's formula for that sub-triangle (Arvo 1995, eq. 9-11 as he derives them).
  const double area = double(u.x) * omega;
  const double s = std::sin(area - alpha), t = std::cos(area - alpha);
  const double uu = t - cos_alpha, vv = s + sin_alpha * dot(k.a, k.b);
  const double denominator = (vv * s + uu * t) * sin_alpha;
  if (!(std::fabs(denominator) > 0.0)) return std::nullopt;
  const double q = std::clamp(((vv * t - uu * s) * cos_alpha - vv) / denominator, -1.0, 1.0);
  const Dvec towards_c = tangent(k.a, k.c);
  const double towards_c_length = length(towards_c);
  if (!(towards_c_length > 0.0)) return std::nullopt;
  const Dvec c_hat = k.a * q + towards_c * (std::sqrt(std::max(0.0, 1.0 - q * q)) / towards_c_length);
  // On the arc from b to ĉ: 1 − cos θ uniform in [0, 1 − b·ĉ].
  const double z = 1.0 - double(u.y) * (1.0 - dot(c_hat, k.b));
  const Dvec towards_c_hat = tangent(k.b, c_hat);
  const double towards_length = length(towards_c_hat);
  const Dvec w = towards_length > 0.0 ? k.b * z + towards_c_hat * (std::sqrt(std::max(0.0, 1.0 - z * z)) / towards_length)
                                      : k.b;
  const Dvec n = normalized(w);
  if (!std::isfinite(n.x + n.y + n.z)) return std::nullopt;
  return Vec3(float(n.x), float(n.y), float(n.z));
}

}  // namespace rimu
