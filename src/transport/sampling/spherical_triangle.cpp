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

// The interior angle at a between the arcs to b and to c.
double corner_angle(Dvec a, Dvec b, Dvec c) {
  const Dvec tb = tangent(a, b), tc = tangent(a, c);
  return std::atan2(length(cross(tb, tc)), dot(tb, tc));
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

double excess(const Corners& k, double& alpha) {
  alpha = corner_angle(k.a, k.b, k.c);
  const double omega = alpha + corner_angle(k.b, k.c, k.a) + corner_angle(k.c, k.a, k.b) - std::numbers::pi;
  return std::isfinite(omega) ? std::max(0.0, omega) : 0.0;
}

}  // namespace

double spherical_triangle_solid_angle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2) {
  const Corners k = corners_from(p, v0, v1, v2);
  if (!k.valid) return 0.0;
  double alpha = 0.0;
  return excess(k, alpha);
}

std::optional<Vec3> sample_spherical_triangle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2, Vec2 u) {
  const Corners k = corners_from(p, v0, v1, v2);
  if (!k.valid) return std::nullopt;
  double alpha = 0.0;
  const double omega = excess(k, alpha);
  if (!(omega > 0.0)) return std::nullopt;
  // The sub-triangle (a, b, ĉ) of area Â = u₁Ω: ĉ = q a + √(1 − q²) ĉ⊥, ĉ⊥ the unit tangent at a towards c, where
  // q = cos of the arc a–ĉ solves Girard's formula for that sub-triangle (Arvo 1995, eq. 9-11 as he derives them).
  const double area = double(u.x) * omega;
  const double s = std::sin(area - alpha), t = std::cos(area - alpha);
  const double cos_alpha = std::cos(alpha), sin_alpha = std::sin(alpha);
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
