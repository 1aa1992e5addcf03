// What the light BVH knows of one light, or of a cluster of lights: where it is, how bright it can be, and in which
// directions it can shine. The importance function estimates how much the cluster can contribute at a shading
// point; the BVH sampler (bvh_light_sampler.h) descends the tree in proportion to it.
//
// Bounds (after Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting"):
// - an axis-aligned box holding every emitting point;
// - intensity_w_sr: an upper bound of the radiant intensity ∫I(λ)dλ (360-830 nm, W/sr) the cluster can send in any
//   one direction: a point light's I, a spot's on-axis I, an IES profile's peak, a Lambertian triangle's L·A. A
//   cluster holds the sum of its members' bounds. (Conty & Kulla and pbrt-v4 use the power Φ instead; intensity is
//   what a receiver sees, so a 1 W/sr point light and a 1 W/sr triangle facing the receiver get the same importance,
//   where Φ would give the point light 4π/π = 4 times more.)
// - an orientation cone (axis, θo) holding every emitter's normal or emission axis, and θe: how far beyond θo
//   the emission can still reach (π/2 for Lambertian surfaces, outer − inner for a spot). A direction more than
//   θo + θe from the axis receives nothing. two_sided: the mirrored cone (−axis) emits as well.
// - plane_offset_m, for half-space clusters: every member emits only into the open half-space in front of its own
//   points along `axis` (axis·ω > 0 for every emitted direction ω): one-sided emitters that all face exactly `axis`
//   (a flat emitter, a ceiling of panels) and emitters at a point whose cone and falloff reach at most 90° from
//   `axis` (a ceiling of downlights, spots of ≤ 180° outer cone). plane_offset_m is the min over emitting points y of
//   axis·y; a point p with axis·p ≤ plane_offset_m is behind every emitter: exact culling of the back of a one-sided
//   area light, and of the ceiling above a downlight.
// - cos_theta_lit: cos θl, θl the largest angle from `axis` within which a direction from any member's point is
//   inside that member's emission cone and falloff (min over members of θo_m + θe_m − ∠(axis_m, axis)); it
//   certifies that every member can reach a point (bvh_light_sampler.cpp, every_leaf_scores). kNoLitCone if no such
//   angle is known.
//
// Importance at a point p with normal n (n = 0: a point in a medium or on a surface that transmits):
//   I · cos θ'_e · cos θ'_i / d²,
// d the distance from the box centre (at least the box's half diagonal), θu the half-angle the box's bounding sphere
// subtends from p (π inside it), θ'_e = max(0, θ_w − θo − θu) the smallest possible angle between an emission cone
// direction and the direction to p, θ'_i = max(0, θ_i − θu) the smallest angle between n and a direction to the box.
// It is 0 when θ'_e ≥ θe (p outside every emission cone), when the whole box lies on or below p's tangent plane
// (n·(y − p) ≤ 0 for every corner y: no light reaches an opaque surface from below, which the integrators enforce
// too), and behind a half-space cluster (plane_offset_m). Both cosines are floored at kImportanceCosineFloor,
// so nothing that can contribute gets importance 0 through rounding at grazing angles.
#pragma once

#include <limits>

#include "transport/geometry/vector.h"

namespace rimu {

inline constexpr float kImportanceCosineFloor = 1e-3f;
/// cos_theta_lit of bounds that certify nothing (no cosine reaches it).
inline constexpr float kNoLitCone = 2.0f;
/// The light tree's certificate (bvh_light_sampler.cpp, every_leaf_scores) tests directions against the lit cone
/// narrowed by twice the bounds' angular margin (1e-3 rad): cos(θl − 2·margin) ≤ cos θl·kLitConeCosMargin +
/// sin θl·kLitConeSinMargin.
inline constexpr float kLitConeCosMargin = 0.999998f, kLitConeSinMargin = 0.002f;

/// The range a part's intensity bound is kept in. The tree only compares intensities, so squeezing an absurd value
/// (a 1e-50 W/sr point light, a 1e35 W/sr sun stand-in) into it changes how often a light is picked, never whether it
/// can be: every light with power stays a leaf with a positive bound, and the sum over a million leaves stays finite.
inline constexpr double kSmallestIntensityBoundWsr = 1e-30;
inline constexpr double kLargestIntensityBoundWsr = 1e30;

/// `intensity_w_sr` as a tree bound: 0 for 0, negative or NaN; otherwise clamped into the range above.
float intensity_bound(double intensity_w_sr);

struct LightBounds {
  Vec3 lower_m{}, upper_m{};
  float intensity_w_sr = 0.0f;
  Vec3 axis{0, 0, 1};        ///< unit
  float cos_theta_o = 1.0f;  ///< cos of the cone half-angle holding every emitter's axis/normal
  float cos_theta_e = 0.0f;  ///< cos of the extra angle beyond θo the emission reaches
  bool two_sided = false;
  /// Valid when half_space: min over emitting points y of axis·y.
  float plane_offset_m = -std::numeric_limits<float>::infinity();
  bool half_space = false;
  float cos_theta_lit = kNoLitCone;  ///< see above

  Vec3 centre_m() const { return (lower_m + upper_m) * 0.5f; }
};

/// LightBounds in the form the importance is evaluated from, with what every evaluation would otherwise recompute
/// (centre, half extent, bounding-sphere radius, sin θo) worked out once: the light tree's nodes hold these.
struct ImportanceBounds {
  Vec3 centre_m{}, half_m{};
  float radius2_m2 = 0.0f, radius_m = 0.0f;  ///< of the box's bounding sphere (the half diagonal)
  Vec3 axis{0, 0, 1};
  float cos_theta_o = 1.0f, sin_theta_o = 0.0f, cos_theta_e = 0.0f, cos_theta_lit = kNoLitCone;
  float intensity_w_sr = 0.0f;
  float plane_offset_m = -std::numeric_limits<float>::infinity();
  bool two_sided = false, half_space = false;

  static ImportanceBounds of(const LightBounds& b);
};

/// Bounds of an emitter at one point (point, spot, IES), emitting into the cone (axis, θo) with falloff to θo + θe.
LightBounds point_light_bounds(Vec3 position_m, double intensity_w_sr, Vec3 axis, double theta_o_rad,
                               double theta_e_rad);
/// Bounds of a Lambertian triangle of radiance integral `radiance_w_m2_sr` (∫L dλ) with unit front normal `normal`.
LightBounds triangle_light_bounds(Vec3 v0, Vec3 v1, Vec3 v2, Vec3 normal, double area_m2, double radiance_w_m2_sr,
                                  bool two_sided);

/// Bounds of a Lambertian sphere (outward-facing, or two-sided) of radius `radius_m` and radiance integral
/// `radiance_w_m2_sr`: its box, every direction as a normal (θo = π, θe = π/2), and the intensity πr²·L it shows in
/// every direction (its silhouette's area times L). A two-sided sphere's inside is within its box, where the
/// importance takes every direction anyway, so its bounds are the same.
LightBounds sphere_light_bounds(Vec3 centre_m, float radius_m, double radiance_w_m2_sr);

/// The bounds of the union of two clusters (a cluster with zero intensity is ignored); its cos_theta_lit is
/// kNoLitCone (the build's node bounds work it out from the members instead).
LightBounds unite(const LightBounds& a, const LightBounds& b);

/// The importance above, ≥ 0 and finite. `normal`: unit or zero. About 60-90 instructions (4 square roots, 1
/// division); the LightBounds form converts first and returns exactly the same value.
float light_importance(const ImportanceBounds& b, Vec3 p, Vec3 normal);
float light_importance(const LightBounds& b, Vec3 p, Vec3 normal);

/// Conty & Kulla's orientation measure M_Ω = 2π(1 − cos θo) + π/2 (2θw sin θo − cos(θo − 2θw) − 2θo sin θo + cos θo),
/// θw = min(θo + θe, π): the solid-angle-like size of the cluster's emission directions, for the build's cost.
double orientation_measure(const LightBounds& b);

}  // namespace rimu
