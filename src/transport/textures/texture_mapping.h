// Where a texture is looked up: pbrt-v4's texture mappings from a surface point to texture coordinates.
#pragma once

#include <cmath>
#include <numbers>

#include "transport/textures/material_context.h"
#include "transport/geometry/transform.h"

namespace rimu {

/// Texture coordinates and their derivatives per film step: where an image is read, and how wide around it.
struct TextureFootprint {
  Vec2 st;
  Vec2 dst_dx, dst_dy;  ///< (∂s/∂x, ∂t/∂x), (∂s/∂y, ∂t/∂y); zero: no footprint known
};

/// pbrt-v4's 2D "uv" texture mapping: (s, t) = (su·u + du, sv·v + dv).
struct UvMapping {
  float su = 1, sv = 1, du = 0, dv = 0;
  Vec2 operator()(Vec2 uv) const { return {su * uv.x + du, sv * uv.y + dv}; }
};

/// How a 2D texture gets (s, t), or a 3D texture its point, from a surface point (pbrt-v4's TextureMapping2D and
/// TextureMapping3D). All but `uv` work on the hit's world position p, first carried into texture space by
/// `texture_from_world` (the inverse of where the texture was placed), pₜ = (x, y, z):
///   uv:          the UvMapping of the surface's own (u, v);
///   spherical:   s = θ/π, t = φ/2π, θ the angle of pₜ from +z, φ = atan2(y, x) in [0, 2π) (pbrt-v4's order: s is θ);
///   cylindrical: s = (π + atan2(y, x))/2π, t = z;
///   planar:      s = ds + pₜ·vs, t = dt + pₜ·vt;
///   solid:       the 3D point pₜ itself (3D textures: noise, 3D checkerboard).
struct TextureMapping {
  enum class Kind { uv, spherical, cylindrical, planar, solid };
  Kind kind = Kind::uv;
  UvMapping uv;
  Transform texture_from_world;
  Vec3 planar_s{1, 0, 0}, planar_t{0, 1, 0};
  Vec2 planar_offset;

  TextureMapping() = default;
  TextureMapping(UvMapping m) : uv(m) {}  // NOLINT: implicit, a uv mapping is a texture mapping
  static TextureMapping solid(const Transform& texture_from_world) {
    TextureMapping m;
    m.kind = Kind::solid;
    m.texture_from_world = texture_from_world;
    return m;
  }

  /// True for the surface's own (u, v) unchanged: a lookup through it can be skipped.
  bool is_identity_uv() const { return kind == Kind::uv && uv.su == 1 && uv.sv == 1 && uv.du == 0 && uv.dv == 0; }

  /// The 3D texture-space point (every kind: what a solid texture reads).
  Vec3 point(const MaterialContext& c) const { return texture_from_world.point(c.position); }

  /// st() for an image lookup: a mapping can overflow (a huge uv_scale, a far point under a planar mapping) and an
  /// image's texel index must stay defined, so a non-finite (s, t) reads at (0, 0).
  Vec2 image_st(const MaterialContext& c) const {
    const Vec2 s = st(c);
    return std::isfinite(s.x) && std::isfinite(s.y) ? s : Vec2{0.0f, 0.0f};
  }

  /// image_st() with its derivatives: the uv mapping's are the surface's scaled; the others' are differenced over
  /// the footprint (st at p + ∂p/∂x less st at p: exact for planar, the chord for spherical and cylindrical, taken
  /// the short way round their seams). Zero when the context has no footprint or a coordinate is not finite.
  TextureFootprint image_footprint(const MaterialContext& c) const {
    TextureFootprint f{image_st(c), {}, {}};
    if (kind == Kind::uv) {
      f.dst_dx = {uv.su * c.duvdx.x, uv.sv * c.duvdx.y};
      f.dst_dy = {uv.su * c.duvdy.x, uv.sv * c.duvdy.y};
    } else if (!(c.dpdx == Vec3{}) || !(c.dpdy == Vec3{})) {
      const auto difference = [&](Vec3 dp) {
        MaterialContext shifted = c;
        shifted.position = c.position + dp;
        const Vec2 s = st(shifted);
        Vec2 d{s.x - f.st.x, s.y - f.st.y};
        // Spherical t and cylindrical s are angles over 2π: a step across the seam is the short way round.
        if (kind == Kind::spherical) d.y -= std::round(d.y);
        if (kind == Kind::cylindrical) d.x -= std::round(d.x);
        return std::isfinite(d.x) && std::isfinite(d.y) ? d : Vec2{};
      };
      f.dst_dx = difference(c.dpdx);
      f.dst_dy = difference(c.dpdy);
    }
    return f;
  }

  /// The 2D texture coordinates (for `solid`, the point's x and y).
  Vec2 st(const MaterialContext& c) const {
    constexpr float kPi = std::numbers::pi_v<float>;
    if (kind == Kind::uv) return uv(c.uv);
    const Vec3 p = point(c);
    switch (kind) {
      case Kind::spherical: {
        const float r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
        const float cos_theta = r > 0.0f ? std::fmin(1.0f, std::fmax(-1.0f, p.z / r)) : 1.0f;
        float phi = std::atan2(p.y, p.x);
        if (phi < 0.0f) phi += 2.0f * kPi;
        return {std::acos(cos_theta) / kPi, phi / (2.0f * kPi)};
      }
      case Kind::cylindrical: return {(kPi + std::atan2(p.y, p.x)) / (2.0f * kPi), p.z};
      case Kind::planar:
        return {planar_offset.x + dot(p, planar_s), planar_offset.y + dot(p, planar_t)};
      default: return {p.x, p.y};
    }
  }
};

}  // namespace rimu
