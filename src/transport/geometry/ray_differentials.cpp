#include "transport/geometry/ray_differentials.h"

#include <algorithm>
#include <cmath>

namespace rimu {
namespace {

constexpr float kMaxDerivative = 1e8f;

float clamp_derivative(float v) { return std::isfinite(v) ? std::clamp(v, -kMaxDerivative, kMaxDerivative) : 0.0f; }

// The direction −w leaves with after a mirror (or, transmitted, a refraction of relative index eta) about unit n;
// w points away from the surface, on either side. nullopt on total internal reflection.
std::optional<Vec3> bend(Vec3 w, Vec3 n, bool transmitted, float eta) {
  const float cos_i = dot(w, n);
  if (!transmitted) return n * (2.0f * cos_i) - w;
  // Snell's law with n turned to w's side: sin²θt = sin²θi / η², the refracted ray on the far side.
  const Vec3 nf = cos_i < 0.0f ? -n : n;
  const float ci = std::fabs(cos_i);
  const float sin2_t = std::fmax(0.0f, 1.0f - ci * ci) / (eta * eta);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float ct = std::sqrt(1.0f - sin2_t);
  return normalize(-w / eta + nf * (ci / eta - ct));
}

}  // namespace

SurfaceDifferentials surface_differentials(Vec3 p, Vec3 n, Vec3 dpdu, Vec3 dpdv, const RayDifferentials& rays) {
  SurfaceDifferentials d;
  const float nx = dot(n, rays.rx_direction), ny = dot(n, rays.ry_direction);
  if (nx == 0.0f || ny == 0.0f) return d;
  const float plane = dot(n, p);
  const float tx = (plane - dot(n, rays.rx_origin)) / nx, ty = (plane - dot(n, rays.ry_origin)) / ny;
  if (!std::isfinite(tx) || !std::isfinite(ty)) return d;
  d.dpdx = rays.rx_origin + rays.rx_direction * tx - p;
  d.dpdy = rays.ry_origin + rays.ry_direction * ty - p;
  // Normal equations AᵀA [∂u ∂v]ᵀ = Aᵀ ∂p with A = [∂p/∂u ∂p/∂v].
  const float a00 = dot(dpdu, dpdu), a01 = dot(dpdu, dpdv), a11 = dot(dpdv, dpdv);
  const float det = a00 * a11 - a01 * a01;
  const float inv_det = det != 0.0f && std::isfinite(1.0f / det) ? 1.0f / det : 0.0f;
  const auto solve = [&](Vec3 dp) {
    const float b0 = dot(dpdu, dp), b1 = dot(dpdv, dp);
    return Vec2{clamp_derivative((a11 * b0 - a01 * b1) * inv_det), clamp_derivative((a00 * b1 - a01 * b0) * inv_det)};
  };
  d.duvdx = solve(d.dpdx);
  d.duvdy = solve(d.dpdy);
  return d;
}

std::optional<RayDifferentials> specular_differentials(const RayDifferentials& incoming, Vec3 p, Vec3 n,
                                                       const SurfaceDifferentials& d, bool transmitted, float eta) {
  const auto x = bend(-incoming.rx_direction, n, transmitted, eta);
  const auto y = bend(-incoming.ry_direction, n, transmitted, eta);
  if (!x || !y) return std::nullopt;
  return RayDifferentials{p + d.dpdx, normalize(*x), p + d.dpdy, normalize(*y)};
}

}  // namespace rimu
