// What a material sees of the surface point it is asked about.
#pragma once

#include <bit>
#include <cstdint>

#include "transport/sampling/bit_mixing.h"
#include "transport/geometry/surface_hit.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// The surface point a material (or texture) is evaluated at, in world space. Built once per hit by the integrator
/// (MaterialContext::at) and passed by reference. Vectors left zero mean "not known" (MaterialContext::at_uv: a
/// point known only by its texture coordinates).
struct MaterialContext {
  Vec2 uv;                ///< texture coordinates
  Vec3 position;          ///< the hit point
  Vec3 geometric_normal;  ///< unit; the surface's front side (not flipped towards wo)
  /// unit; interpolated vertex normal on the geometric normal's side — or, once the integrator has asked
  /// Material::shading_normal, the material's normal- or bump-mapped one (what its BSDF is built around)
  Vec3 shading_normal;
  /// ∂p/∂u and ∂p/∂v: the surface's tangents along the texture axes (from the triangle's uvs, its barycentrics when
  /// the mesh has none, or a sphere's parametrisation). Zero where the uv parametrisation is degenerate, and in
  /// scenes loaded from files where no material has a normal or bump map (EmbreeScene::set_surface_tangents).
  Vec3 dpdu, dpdv;
  Vec3 wo;                ///< unit; towards where the light leaves (the previous vertex)
  /// The footprint of the path's ray around this point, per film sample step (transport/geometry/ray_differentials.h):
  /// ∂p/∂x, ∂p/∂y and the texture coordinates' (∂u/∂x, ∂v/∂x), (∂u/∂y, ∂v/∂y). Zero when not known — after a
  /// diffuse or glossy bounce, or in scenes without image textures or bump maps, which skip computing them
  /// (TransportScene::texture_footprints): image textures then read their finest level.
  Vec3 dpdx, dpdy;
  Vec2 duvdx, duvdy;

  static MaterialContext at(const SurfaceHit& hit, Vec3 wo_world) {
    return {hit.uv, hit.position, hit.geometric_normal, hit.shading_normal, hit.dpdu, hit.dpdv, wo_world, {}, {}, {}, {}};
  }

  static MaterialContext at_uv(Vec2 uv) {
    MaterialContext c;
    c.uv = uv;
    return c;
  }

  /// A deterministic 32-bit hash of the hit (position and wo, as pbrt-v4's MixMaterial hashes them): the same
  /// point seen from the same direction always gets the same value, so every query made at one vertex agrees,
  /// while neighbouring points are decorrelated. Computed on demand (six integer hash rounds): only stochastic
  /// materials pay for it.
  uint32_t hash() const {
    uint32_t h = hash32(std::bit_cast<uint32_t>(position.x));
    for (float f : {position.y, position.z, wo.x, wo.y, wo.z}) h = hash32(h ^ std::bit_cast<uint32_t>(f));
    return h;
  }
};

/// A uniform value in [0, 1) from 24 bits of `h`.
inline float unit_float_from_hash(uint32_t h) { return float(h >> 8) * 0x1p-24f; }

}  // namespace rimu
