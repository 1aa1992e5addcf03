// Normal and bump maps: a material's own shading normal, computed per hit before its BSDF is built.
#pragma once

#include <memory>

#include "transport/textures/float_texture.h"
#include "transport/textures/material_context.h"

namespace rimu {

/// A tangent-space normal per surface point: (x, y, z) in the frame (∂p/∂u, n × ∂p/∂u, n), not necessarily unit
/// (an RGB image decoded as 2·rgb − 1, pbrt-v4's convention). Immutable, called from many threads.
class TangentNormalTexture {
 public:
  virtual ~TangentNormalTexture() = default;
  virtual Vec3 evaluate(Vec2 uv) const = 0;
};

/// The smallest cosine a perturbed normal keeps with the geometric normal's side (see keep_above_surface).
inline constexpr float kMinPerturbedCosine = 0.01f;

/// `n` if it lies at least kMinPerturbedCosine above the surface of unit geometric normal `ng`; else `n` bent
/// towards `ng` until it does (its tangential direction kept). A shading normal below the geometric surface would
/// make every direction that leaves the surface a "back" direction of the BSDF (black) and every direction the BSDF
/// samples one that enters the surface (rejected by the integrators): bending keeps the map's look at grazing
/// tilts without letting light through — the integrators still test light and sampled directions against ng.
Vec3 keep_above_surface(Vec3 n, Vec3 ng);

/// The world-space normal that tangent-space `tangent_normal` stands for at a surface point of unit shading normal
/// `ns` and tangent `dpdu` (pbrt-v4's NormalMap: s = ∂p/∂u made orthogonal to ns, t = ns × s). Falls back to `ns`
/// where ∂p/∂u is zero or (within 1e-3 rad) parallel to ns, or where the map's vector is zero or not finite. The
/// result is unit and kept above the geometric surface (keep_above_surface).
Vec3 map_tangent_normal(Vec3 ns, Vec3 ng, Vec3 dpdu, Vec3 tangent_normal);

/// The step in (u, v) over which a bump map's displacement is differenced where the hit has no footprint (after a
/// diffuse bounce): pbrt-v4's fallback, 1/2000 of the uv square, two texels of a 4096² map — small enough to follow
/// detail at film resolutions, large enough that float differences of the displacement stay well above rounding.
inline constexpr float kBumpStepUv = 0.0005f;

/// The bump map's differencing steps (Δu, Δv) at a surface point: half the footprint along each texture axis,
/// Δu = ½(|∂u/∂x| + |∂u/∂y|) and likewise Δv (pbrt-v4's rule: the displacement's slope is then taken over about the
/// area one sample sees, so a distant bumpy floor is not differenced finer than it is filtered), kBumpStepUv
/// where that is zero.
Vec2 bump_steps_uv(const MaterialContext& context);

/// The bumped shading normal (pbrt-v4's BumpMap): displacement d(u, v) along ns moves the tangents to
/// ∂p/∂u + (d(u + Δu, v) − d(u, v))/Δu · ns and likewise along v (bump_steps_uv; the tangents are first made
/// orthogonal to ns); the normal is their cross product, oriented as ∂p/∂u × ∂p/∂v is against ns. pbrt's extra
/// d·∂n/∂u terms are left out (Rimu does not carry ∂n/∂u; they vanish on flat faces and matter only where the
/// displacement is a sizeable fraction of the curvature radius). Falls back to ns where a tangent is zero, they are
/// parallel, or a displacement is not finite; kept above the geometric surface.
Vec3 bump_normal(const MaterialContext& context, const FloatTexture& displacement);

/// A material's replacement of the shading normal: a normal map or a bump map (one or the other).
class ShadingNormalModifier {
 public:
  static std::shared_ptr<const ShadingNormalModifier> normal_map(std::shared_ptr<const TangentNormalTexture> map);
  static std::shared_ptr<const ShadingNormalModifier> bump(FloatTexturePtr displacement);

  /// The unit shading normal at `context` (on ng's side).
  Vec3 shading_normal(const MaterialContext& context) const;

 private:
  std::shared_ptr<const TangentNormalTexture> normal_map_;
  FloatTexturePtr displacement_;
};

}  // namespace rimu
