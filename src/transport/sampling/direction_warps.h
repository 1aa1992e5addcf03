// Warps from the unit square to directions and disk points, with their densities.
#pragma once

#include <cmath>
#include <numbers>

#include "transport/geometry/vector.h"

namespace rimu {

/// A point on the unit disk from u ∈ [0,1)², area-preserving and low-distortion (Shirley & Chiu 1997,
/// "A Low Distortion Map Between Disk and Square", concentric map): square rings map to circles.
inline Vec2 sample_concentric_disk(Vec2 u) {
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  const float quarter_pi = 0.25f * std::numbers::pi_v<float>;
  float r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = quarter_pi * (b / a);
  } else {
    r = b;
    phi = 2.0f * quarter_pi - quarter_pi * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

/// A direction in the upper hemisphere (z ≥ 0) with density cos θ / π per steradian (Malley's method: a uniform
/// disk point lifted onto the hemisphere).
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
  const Vec2 d = sample_concentric_disk(u);
  const float z = std::sqrt(std::fmax(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

/// The density of sample_cosine_hemisphere, per steradian: |cos θ| / π.
inline float cosine_hemisphere_pdf(float abs_cos_theta) { return abs_cos_theta * std::numbers::inv_pi_v<float>; }

}  // namespace rimu
