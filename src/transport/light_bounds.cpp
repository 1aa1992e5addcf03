#include "transport/light_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rimu {
namespace {

constexpr double kPi = std::numbers::pi;
// Angles are widened by this much (rad) wherever bounds are computed, so that float rounding in the importance
// (cosines near 1 resolve angles to ~5e-4 rad) can never cut off a direction the light reaches.
constexpr double kAngleMarginRad = 1e-3;

struct CosSin {
  float cos, sin;
};

// cos and sin of max(0, a − b) for angles a, b in [0, π], from their cosines and sines.
inline CosSin angle_difference_clamped(float cos_a, float sin_a, float cos_b, float sin_b) {
  if (cos_a >= cos_b) return {1.0f, 0.0f};
  return {cos_a * cos_b + sin_a * sin_b, sin_a * cos_b - cos_a * sin_b};
}

// (std::max, not std::fmax: without -ffast-math fmax is a library call, and these inputs are never NaN.)
inline float sine_of(float cos_x) { return std::sqrt(std::max(0.0f, 1.0f - cos_x * cos_x)); }

double angle_of(float cos_x) { return std::acos(std::clamp(double(cos_x), -1.0, 1.0)); }

Vec3 min3(Vec3 a, Vec3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
Vec3 max3(Vec3 a, Vec3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }

// The smallest cone (axis, half-angle) found by the usual construction that holds both cones: if one holds the
// other it is the answer; otherwise the cone through both far edges, half-angle (θa + θd + θb)/2.
void unite_cones(Vec3 axis_a, double theta_a, Vec3 axis_b, double theta_b, Vec3& axis, double& theta) {
  if (axis_a == axis_b) {
    axis = axis_a;
    theta = std::max(theta_a, theta_b);
    return;
  }
  const double cos_d = std::clamp(double(dot(axis_a, axis_b)), -1.0, 1.0);
  const double theta_d = std::acos(cos_d);
  if (theta_d + theta_b <= theta_a) {
    axis = axis_a;
    theta = theta_a + kAngleMarginRad * 0.1;
    return;
  }
  if (theta_d + theta_a <= theta_b) {
    axis = axis_b;
    theta = theta_b + kAngleMarginRad * 0.1;
    return;
  }
  const double half = 0.5 * (theta_a + theta_d + theta_b);
  if (half >= kPi) {
    axis = axis_a;
    theta = kPi;
    return;
  }
  // Rotate axis_a towards axis_b by half − θa in their common plane.
  const Vec3 perpendicular = axis_b - axis_a * float(cos_d);
  const float perpendicular_length = length(perpendicular);
  if (!(perpendicular_length > 1e-7f)) {  // (anti)parallel axes that neither cone holds: take the sphere
    axis = axis_a;
    theta = kPi;
    return;
  }
  const Vec3 towards = perpendicular / perpendicular_length;
  const double rotation = half - theta_a;
  axis = normalize(axis_a * float(std::cos(rotation)) + towards * float(std::sin(rotation)));
  theta = std::min(kPi, half + kAngleMarginRad * 0.1);
}

}  // namespace

float intensity_bound(double intensity_w_sr) {
  if (!(intensity_w_sr > 0.0)) return 0.0f;
  return float(std::clamp(intensity_w_sr, kSmallestIntensityBoundWsr, kLargestIntensityBoundWsr));
}

LightBounds point_light_bounds(Vec3 position_m, double intensity_w_sr, Vec3 axis, double theta_o_rad,
                               double theta_e_rad) {
  LightBounds b;
  b.lower_m = b.upper_m = position_m;
  b.intensity_w_sr = intensity_bound(intensity_w_sr);
  b.axis = normalize(axis);
  b.cos_theta_o = float(std::cos(std::clamp(theta_o_rad, 0.0, kPi)));
  b.cos_theta_e = float(std::cos(std::clamp(theta_e_rad + kAngleMarginRad, 0.0, kPi)));
  return b;
}

LightBounds triangle_light_bounds(Vec3 v0, Vec3 v1, Vec3 v2, Vec3 normal, double area_m2, double radiance_w_m2_sr,
                                  bool two_sided) {
  LightBounds b;
  b.lower_m = min3(v0, min3(v1, v2));
  b.upper_m = max3(v0, max3(v1, v2));
  b.intensity_w_sr = intensity_bound(area_m2 * radiance_w_m2_sr);  // L·A·cos θ, largest along the normal
  b.axis = normal;
  b.cos_theta_o = 1.0f;
  b.cos_theta_e = float(std::cos(kPi / 2 + kAngleMarginRad));
  b.two_sided = two_sided;
  b.flat_one_sided = !two_sided;
  b.plane_offset_m = std::fmin(dot(normal, v0), std::fmin(dot(normal, v1), dot(normal, v2)));
  return b;
}

LightBounds unite(const LightBounds& a, const LightBounds& b) {
  if (!(a.intensity_w_sr > 0.0f)) return b;
  if (!(b.intensity_w_sr > 0.0f)) return a;
  LightBounds u;
  u.lower_m = min3(a.lower_m, b.lower_m);
  u.upper_m = max3(a.upper_m, b.upper_m);
  u.intensity_w_sr = a.intensity_w_sr + b.intensity_w_sr;
  double theta_o = 0.0;
  unite_cones(a.axis, angle_of(a.cos_theta_o), b.axis, angle_of(b.cos_theta_o), u.axis, theta_o);
  u.cos_theta_o = a.axis == b.axis ? std::fmin(a.cos_theta_o, b.cos_theta_o) : float(std::cos(theta_o));
  u.cos_theta_e = std::fmin(a.cos_theta_e, b.cos_theta_e);
  u.two_sided = a.two_sided || b.two_sided;
  u.flat_one_sided = a.flat_one_sided && b.flat_one_sided && a.axis == b.axis;
  if (u.flat_one_sided) u.plane_offset_m = std::fmin(a.plane_offset_m, b.plane_offset_m);
  return u;
}

float light_importance(const LightBounds& b, Vec3 p, Vec3 normal) {
  if (!(b.intensity_w_sr > 0.0f)) return 0.0f;
  const Vec3 centre = b.centre_m();
  const Vec3 half = (b.upper_m - b.lower_m) * 0.5f;
  const Vec3 to_p = p - centre;
  const bool oriented = !(normal == Vec3{});
  // The largest n·(y − p) over the box's corners y: ≤ 0 means the box is on or below the tangent plane.
  if (oriented && !(-dot(normal, to_p) + dot(abs(normal), half) > 0.0f)) return 0.0f;
  if (b.flat_one_sided && !(dot(b.axis, p) > b.plane_offset_m)) return 0.0f;

  const float distance2 = length_squared(to_p);
  const float radius2 = length_squared(half);
  constexpr float kLargest = 1e30f;
  // Past the tests above the cluster can contribute, so its importance must not round to 0 (a faint light far away
  // would then never be picked by next-event estimation and, if it is a point light, never reached at all).
  constexpr float kSmallest = std::numeric_limits<float>::min();
  if (distance2 <= radius2) {
    // p inside the bounding sphere: every direction is possible; the distance is taken as the sphere's radius.
    if (!(radius2 > 0.0f)) return 0.0f;  // p at a point light
    return std::clamp(b.intensity_w_sr / radius2, kSmallest, kLargest);
  }
  const float sin2_u = radius2 / distance2;
  const float sin_u = std::sqrt(sin2_u), cos_u = std::sqrt(1.0f - sin2_u);
  const Vec3 w = to_p / std::sqrt(distance2);  // from the cluster towards p

  float cos_w = dot(b.axis, w);
  if (b.two_sided) cos_w = std::fabs(cos_w);
  const CosSin beyond_cone = angle_difference_clamped(cos_w, sine_of(cos_w), b.cos_theta_o, sine_of(b.cos_theta_o));
  const CosSin emission = angle_difference_clamped(beyond_cone.cos, beyond_cone.sin, cos_u, sin_u);
  if (emission.cos < b.cos_theta_e) return 0.0f;

  float receiver = 1.0f;
  if (oriented) {
    const float cos_i = -dot(normal, w);
    receiver = std::max(angle_difference_clamped(cos_i, sine_of(cos_i), cos_u, sin_u).cos, kImportanceCosineFloor);
  }
  const float importance =
      b.intensity_w_sr * std::max(emission.cos, kImportanceCosineFloor) * receiver / distance2;
  return std::clamp(importance, kSmallest, kLargest);
}

double orientation_measure(const LightBounds& b) {
  const double theta_o = angle_of(b.cos_theta_o);
  const double theta_e = angle_of(b.cos_theta_e);
  const double theta_w = std::min(theta_o + theta_e, kPi);
  const double sin_o = std::sin(theta_o);
  return 2.0 * kPi * (1.0 - std::cos(theta_o)) +
         kPi / 2.0 * (2.0 * theta_w * sin_o - std::cos(theta_o - 2.0 * theta_w) - 2.0 * theta_o * sin_o +
                      std::cos(theta_o));
}

}  // namespace rimu
