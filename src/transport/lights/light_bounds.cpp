#include "transport/lights/light_bounds.h"
#include "spectral/math_constants.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <immintrin.h>

namespace rimu {
namespace {

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

// The correctly rounded square root (as std::sqrt) without its errno branch: these inputs are never negative.
inline float root(float x) { return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))); }

// (std::max, not std::fmax: without -ffast-math fmax is a library call, and these inputs are never NaN.)
inline float sine_of(float cos_x) { return root(std::max(0.0f, 1.0f - cos_x * cos_x)); }

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
  // The reach without the rounding margin: an emitter whose intensity is 0 from 90° on lights nothing behind its
  // own plane (a downlight's ceiling).
  const double reach = std::clamp(theta_o_rad, 0.0, kPi) + std::clamp(theta_e_rad, 0.0, kPi);
  if (reach <= kPi / 2) {
    b.half_space = true;
    b.plane_offset_m = dot(b.axis, position_m);
  }
  b.cos_theta_lit = float(std::cos(std::min(reach + kAngleMarginRad, kPi)));
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
  b.half_space = !two_sided;
  b.plane_offset_m = std::fmin(dot(normal, v0), std::fmin(dot(normal, v1), dot(normal, v2)));
  if (!two_sided) b.cos_theta_lit = b.cos_theta_e;  // θo = 0
  return b;
}

LightBounds sphere_light_bounds(Vec3 centre_m, float radius_m, double radiance_w_m2_sr) {
  LightBounds b;
  // The box widened by a float ulp of its coordinates: centre ± radius rounds, and every surface point must be in it.
  const Vec3 half{radius_m, radius_m, radius_m};
  const Vec3 slack = (abs(centre_m) + half) * 1e-6f;
  b.lower_m = centre_m - half - slack;
  b.upper_m = centre_m + half + slack;
  b.intensity_w_sr = intensity_bound(kPi * double(radius_m) * double(radius_m) * radiance_w_m2_sr);
  b.axis = {0, 0, 1};
  b.cos_theta_o = -1.0f;  // θo = π: the normals point everywhere
  b.cos_theta_e = float(std::cos(kPi / 2 + kAngleMarginRad));
  // Every direction from the sphere is within some emitting point's hemisphere: the lit cone is the whole sphere.
  b.cos_theta_lit = -1.0f;
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
  u.half_space = a.half_space && b.half_space && a.axis == b.axis;
  if (u.half_space) u.plane_offset_m = std::fmin(a.plane_offset_m, b.plane_offset_m);
  return u;
}

ImportanceBounds ImportanceBounds::of(const LightBounds& b) {
  ImportanceBounds q;
  q.centre_m = b.centre_m();
  q.half_m = (b.upper_m - b.lower_m) * 0.5f;
  q.radius2_m2 = length_squared(q.half_m);
  q.radius_m = std::sqrt(q.radius2_m2);
  q.axis = b.axis;
  q.cos_theta_o = b.cos_theta_o;
  q.sin_theta_o = sine_of(b.cos_theta_o);
  q.cos_theta_e = b.cos_theta_e;
  q.cos_theta_lit = b.cos_theta_lit;
  q.intensity_w_sr = b.intensity_w_sr;
  q.plane_offset_m = b.plane_offset_m;
  q.two_sided = b.two_sided;
  q.half_space = b.half_space;
  return q;
}

float light_importance(const LightBounds& b, Vec3 p, Vec3 normal) {
  return light_importance(ImportanceBounds::of(b), p, normal);
}

float light_importance(const ImportanceBounds& b, Vec3 p, Vec3 normal) {
  if (!(b.intensity_w_sr > 0.0f)) return 0.0f;
  const Vec3 to_p = p - b.centre_m;
  const bool oriented = !(normal == Vec3{});
  // The largest n·(y − p) over the box's corners y: ≤ 0 means the box is on or below the tangent plane.
  const float normal_dot = dot(normal, to_p);
  if (oriented && !(-normal_dot + dot(abs(normal), b.half_m) > 0.0f)) return 0.0f;
  if (b.half_space && !(dot(b.axis, p) > b.plane_offset_m)) return 0.0f;

  const float distance2 = length_squared(to_p);
  constexpr float kLargest = 1e30f;
  // Past the tests above the cluster can contribute, so its importance must not round to 0 (a faint light far away
  // would then never be picked by next-event estimation and, if it is a point light, never reached at all).
  constexpr float kSmallest = std::numeric_limits<float>::min();
  if (distance2 <= b.radius2_m2) {
    // p inside the bounding sphere: every direction is possible; the distance is taken as the sphere's radius.
    if (!(b.radius2_m2 > 0.0f)) return 0.0f;  // p at a point light
    return std::clamp(b.intensity_w_sr / b.radius2_m2, kSmallest, kLargest);
  }
  const float inverse_distance = 1.0f / root(distance2);
  // θu, the half-angle the bounding sphere subtends: sin θu = r/d (0 for a point).
  const float sin_u = std::min(b.radius_m * inverse_distance, 1.0f);
  const float cos_u = root(std::max(0.0f, 1.0f - sin_u * sin_u));

  // θw, from the axis to the direction from the cluster towards p.
  float cos_w = dot(b.axis, to_p) * inverse_distance;
  if (b.two_sided) cos_w = std::fabs(cos_w);
  // max(0, θw − θo), then less θu (the sines only where the angle is not already 0).
  const CosSin beyond_cone = cos_w >= b.cos_theta_o
                                 ? CosSin{1.0f, 0.0f}
                                 : angle_difference_clamped(cos_w, sine_of(cos_w), b.cos_theta_o, b.sin_theta_o);
  const CosSin emission = angle_difference_clamped(beyond_cone.cos, beyond_cone.sin, cos_u, sin_u);
  if (emission.cos < b.cos_theta_e) return 0.0f;

  float receiver = 1.0f;
  if (oriented) {
    const float cos_i = -normal_dot * inverse_distance;
    receiver = cos_i >= cos_u ? 1.0f
                              : std::max(cos_i * cos_u + sine_of(cos_i) * sin_u, kImportanceCosineFloor);
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
