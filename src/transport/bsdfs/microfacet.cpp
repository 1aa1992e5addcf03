#include "transport/bsdfs/microfacet.h"

#include <cassert>
#include <cmath>
#include <numbers>

namespace rimu {

TrowbridgeReitz::TrowbridgeReitz(float alpha_x, float alpha_y)
    // A floor keeps D finite; any α below kSmoothAlpha is rendered as a delta lobe and never reaches d().
    : alpha_x_(std::fmax(alpha_x, 1e-4f)), alpha_y_(std::fmax(alpha_y, 1e-4f)) {
  assert(alpha_x >= 0.0f && alpha_y >= 0.0f);
}

float TrowbridgeReitz::d(Vec3 m) const {
  // The form in slopes, (m_x/αx)² + (m_y/αy)² + m_z², has no tan θ and so no division by cos θm: it is finite
  // and correct for every unit m, including m on the horizon.
  const float sx = m.x / alpha_x_, sy = m.y / alpha_y_;
  const float e = sx * sx + sy * sy + m.z * m.z;
  return 1.0f / (std::numbers::pi_v<float> * alpha_x_ * alpha_y_ * e * e);
}

float TrowbridgeReitz::lambda(Vec3 w) const {
  // α(φ)² tan²θ = (αx² w_x² + αy² w_y²) / w_z²; at w_z = 0 this is +∞ and Λ = +∞ (G1 = 0), never NaN.
  const float a2_tan2 = (alpha_x_ * alpha_x_ * w.x * w.x + alpha_y_ * alpha_y_ * w.y * w.y) / (w.z * w.z);
  if (!(a2_tan2 < INFINITY)) return INFINITY;
  return 0.5f * (std::sqrt(1.0f + a2_tan2) - 1.0f);
}

float TrowbridgeReitz::visible_d(Vec3 w, Vec3 m) const {
  const float cos_w = std::fabs(w.z);
  // Only normals facing w are visible from it (Heitz 2018, Eq. 1 has ⟨w, m⟩ clamped at 0); m and w are oriented
  // to the same side of the macro surface by the caller's convention, so compare signs of the z components too.
  const float w_dot_m = dot(w, m) * (w.z < 0.0f ? -1.0f : 1.0f) * (m.z < 0.0f ? -1.0f : 1.0f);
  if (cos_w == 0.0f || w_dot_m <= 0.0f) return 0.0f;
  return g1(w) * w_dot_m * d(m) / cos_w;
}

Vec3 TrowbridgeReitz::sample_visible(Vec3 w, Vec2 u) const {
  const float flip = w.z < 0.0f ? -1.0f : 1.0f;
  const Vec3 wu = w * flip;  // upper-hemisphere copy; D is symmetric under z → −z
  // 1. Stretch: the view direction in the configuration where the surface has α = 1.
  const Vec3 vh = normalize(Vec3(alpha_x_ * wu.x, alpha_y_ * wu.y, wu.z));
  // 2. An orthonormal basis around vh (T1 horizontal; any T1 works at normal incidence).
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = cross(vh, t1);
  // 3. A uniform point on the unit disk, then squeeze the half of the disk that the projected hemisphere
  //    covers only partly: the visible projected area of a unit hemisphere seen from vh is the half-disk plus
  //    a half-ellipse of minor radius vh.z.
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::fmax(0.0f, 1.0f - p1 * p1)) + s * p2;
  // 4. Lift the disk point onto the hemisphere around vh.
  const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::fmax(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  // 5. Unstretch the normal back to the α configuration (normals transform with the inverse transpose).
  const Vec3 m = normalize(Vec3(alpha_x_ * nh.x, alpha_y_ * nh.y, std::fmax(1e-7f, nh.z)));
  return m * flip;
}

}  // namespace rimu
