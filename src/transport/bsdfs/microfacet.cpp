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
  return visible_d(d(m), lambda(w), w_dot_m, cos_w);
}

Vec3 TrowbridgeReitz::sample_visible(Vec3 w, Vec2 u) const {
  const float flip = w.z < 0.0f ? -1.0f : 1.0f;
  const Vec3 wu = w * flip;  // upper-hemisphere copy; D is symmetric under z → −z
  // 1. Stretch: the view direction in the configuration where the surface has α = 1.
  const Vec3 vh = normalize(Vec3(alpha_x_ * wu.x, alpha_y_ * wu.y, wu.z));
  // 2. In that configuration the visible normals are the normalised sums vh + c, with c uniform on the spherical
  //    cap of the unit sphere above the plane z = −vh.z (Dupuy & Benyoub 2023, "Sampling Visible GGX Normals with
  //    Spherical Caps", Eq. 8): no basis around vh is needed. z of c is uniform in (−vh.z, 1], its azimuth in
  //    [0, 2π).
  const float z = (1.0f - u.y) * (1.0f + vh.z) - vh.z;
  const float sin_theta = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  const float phi = 2.0f * std::numbers::pi_v<float> * u.x;
  const Vec3 nh(sin_theta * std::cos(phi) + vh.x, sin_theta * std::sin(phi) + vh.y, z + vh.z);
  // 3. Unstretch the (unnormalised) normal back to the α configuration (normals transform with the inverse
  //    transpose) and normalise once. nh.z = (1 − u.y)(1 + vh.z) > 0 for u.y < 1; the floor keeps m off the horizon.
  const Vec3 m = normalize(Vec3(alpha_x_ * nh.x, alpha_y_ * nh.y, std::fmax(1e-7f, nh.z)));
  return m * flip;
}

}  // namespace rimu
