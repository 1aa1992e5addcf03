#include "transport/sampling/equal_area_square.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rimu {

Vec3 equal_area_square_to_sphere(Vec2 p) {
  const float a = 2.0f * std::clamp(p.x, 0.0f, 1.0f) - 1.0f, b = 2.0f * std::clamp(p.y, 0.0f, 1.0f) - 1.0f;
  const float abs_a = std::fabs(a), abs_b = std::fabs(b);
  // Signed distance from the diamond's edge |a| + |b| = 1: positive inside (upper hemisphere).
  const float inside = 1.0f - (abs_a + abs_b);
  const float r = 1.0f - std::fabs(inside);
  // φ within the quadrant, 0 along the a axis and π/2 along the b axis; at r = 0 (a pole) any value will do.
  const float phi = (r == 0.0f ? 1.0f : (abs_b - abs_a) / r + 1.0f) * (std::numbers::pi_v<float> / 4.0f);
  const float z = std::copysign(1.0f - r * r, inside);
  const float radial = r * std::sqrt(std::max(0.0f, 2.0f - r * r));
  return {std::copysign(std::cos(phi), a) * radial, std::copysign(std::sin(phi), b) * radial, z};
}

Vec2 equal_area_sphere_to_square(Vec3 d) {
  const float length_d = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  const float x = std::fabs(d.x) / length_d, y = std::fabs(d.y) / length_d, z = std::fabs(d.z) / length_d;
  // Inverting z = 1 − r² (upper hemisphere; the lower one is mirrored below).
  const float r = std::sqrt(std::max(0.0f, 1.0f - z));
  // φ/(π/2) within the quadrant, from 0 (along x) to 1 (along y).
  const float phi = (x == 0.0f && y == 0.0f) ? 0.0f : std::atan2(y, x) * (2.0f / std::numbers::pi_v<float>);
  float b = phi * r;  // |b| − |a| = r(2φ/(π/2) − 1) and |a| + |b| = r inside the diamond
  float a = r - b;
  if (d.z < 0.0f) {
    // The lower hemisphere lives in the corners: reflect across the quadrant's diagonal edge |a| + |b| = 1.
    std::swap(a, b);
    a = 1.0f - a;
    b = 1.0f - b;
  }
  a = std::copysign(a, d.x);
  b = std::copysign(b, d.y);
  return {std::clamp(0.5f * (a + 1.0f), 0.0f, 1.0f), std::clamp(0.5f * (b + 1.0f), 0.0f, 1.0f)};
}

}  // namespace rimu
