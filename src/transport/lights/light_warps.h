// Warps from the unit square that lights sample with: uniform sphere, uniform cone, uniform triangle.
// (Cosine-weighted hemisphere and the concentric disk live in direction_warps.h.)
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/geometry/vector.h"

namespace rimu {

/// A uniformly distributed unit vector; density 1/(4π) per steradian. z = 1 − 2u.x, φ = 2π u.y.
inline Vec3 sample_uniform_sphere(Vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

/// A direction uniform in solid angle inside the cone around +z with 1 − cos θ_max = `one_minus_cos_max`
/// (passed instead of cos θ_max so that tiny cones, like the sun's 0.27° half-angle, keep their precision:
/// 1 − cos θ = 1.1e-5 there, and float cos θ near 1 would carry a 0.5 % error). Density 1/(2π·one_minus_cos_max).
/// Inverts the CDF of 1 − cos θ, which is uniform on [0, one_minus_cos_max]; sin θ = √((1−cos θ)(1+cos θ)).
inline Vec3 sample_uniform_cone(Vec2 u, float one_minus_cos_max) {
  const float one_minus_cos = u.x * one_minus_cos_max;
  const float cos_theta = 1.0f - one_minus_cos;
  const float sin_theta = std::sqrt(std::fmax(0.0f, one_minus_cos * (2.0f - one_minus_cos)));
  const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

/// 1 − cos of the angle between two unit vectors, accurate for small angles: |a − b|²/2 = 1 − a·b.
inline float one_minus_cos_between(Vec3 a, Vec3 b) { return 0.5f * length_squared(a - b); }

/// Barycentric coordinates (b0, b1, b2) uniform over a triangle's area: b0 = 1 − √u.x, b1 = u.y √u.x
/// (Shirley's square-root map; Turk, "Generating random points in triangles", Graphics Gems, 1990).
inline Vec3 sample_uniform_triangle(Vec2 u) {
  const float s = std::sqrt(u.x);
  const float b0 = 1.0f - s;
  const float b1 = u.y * s;
  return {b0, b1, std::max(0.0f, 1.0f - b0 - b1)};
}

}  // namespace rimu
