// The light tree's importance (light_bounds.h) of four clusters at once, in SSE lanes: the 4-wide light tree
// (bvh_light_sampler.h) evaluates a node's up to four children with one call instead of four.
//
// Each lane computes exactly what light_importance(ImportanceBounds, p, n) computes, operation by operation
// (IEEE single precision, correctly rounded square roots and division, no fused multiply-adds: the project compiles
// for SSE4.1 without contraction), and where the scalar code branches both sides are computed and the lane's side
// selected. So a lane's value is bit for bit the scalar one: a child scores > 0 here exactly where its scalar
// importance does, which the tree's pruning and its witness leaves rely on (tests/transport/light_bounds4_test.cpp).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include <smmintrin.h>

#include "transport/lights/light_bounds.h"

namespace rimu {

/// Up to four ImportanceBounds in structure-of-arrays form; an unused lane has intensity 0 (importance 0).
struct alignas(16) ImportanceBounds4 {
  std::array<float, 4> centre_x{}, centre_y{}, centre_z{};
  std::array<float, 4> half_x{}, half_y{}, half_z{};
  std::array<float, 4> radius2_m2{}, radius_m{};
  std::array<float, 4> axis_x{}, axis_y{}, axis_z{};
  std::array<float, 4> cos_theta_o{}, sin_theta_o{}, cos_theta_e{};
  std::array<float, 4> intensity_w_sr{}, plane_offset_m{};
  /// The certificate's threshold: cos θl·kLitConeCosMargin + sin θl·kLitConeSinMargin, or 3 (never reached) for
  /// bounds that certify nothing (two-sided, or no lit cone).
  std::array<float, 4> certify_threshold{3.0f, 3.0f, 3.0f, 3.0f};
  /// Per lane: all bits set if two-sided / half-space, else 0 (the form SSE masks take).
  std::array<uint32_t, 4> two_sided{}, half_space{};

  void set(int lane, const ImportanceBounds& b);
};

struct Importance4 {
  std::array<float, 4> value;  ///< light_importance of each lane's bounds, bit for bit
  /// Bit j set: lane j's bounds show that every member scores > 0 at (p, n): the box strictly above the tangent
  /// plane, p outside its bounding sphere, and every direction from the box to p within the lit cone less the margin
  /// (the light tree's certificate, bvh_light_sampler.cpp every_leaf_scores, from the quantities the importance
  /// already has; conservative like it, up to rounding far inside the margin).
  int certified;
};

namespace simd4 {
using F = __m128;

inline F load(const std::array<float, 4>& v) { return _mm_load_ps(v.data()); }
inline F splat(float x) { return _mm_set1_ps(x); }
inline F mask(const std::array<uint32_t, 4>& v) { return _mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(v.data()))); }
inline F add(F a, F b) { return _mm_add_ps(a, b); }
inline F sub(F a, F b) { return _mm_sub_ps(a, b); }
inline F mul(F a, F b) { return _mm_mul_ps(a, b); }
// (a if m else b), per lane.
inline F select(F m, F a, F b) { return _mm_blendv_ps(b, a, m); }
// The scalar code's std::max(x, lower) and std::min(x, upper): equal for every input that is not NaN (these never
// are), including the sign of a zero result against a +0 bound.
inline F max_with(F x, F lower) { return _mm_max_ps(x, lower); }
inline F min_with(F x, F upper) { return _mm_min_ps(x, upper); }
// sine_of in light_bounds.cpp: √max(0, 1 − c²).
inline F sine_of(F c) { return _mm_sqrt_ps(max_with(sub(splat(1.0f), mul(c, c)), _mm_setzero_ps())); }
// std::clamp(v, lo, hi) = v < lo ? lo : (hi < v ? hi : v).
inline F clamp(F v, F lo, F hi) { return select(_mm_cmplt_ps(v, lo), lo, select(_mm_cmplt_ps(hi, v), hi, v)); }
// a.x·b.x + a.y·b.y + a.z·b.z in the scalar dot's order.
inline F dot3(F ax, F ay, F az, F bx, F by, F bz) { return add(add(mul(ax, bx), mul(ay, by)), mul(az, bz)); }
}  // namespace simd4

/// A shading point and normal in the form the 4-wide functions below take them: each coordinate in all four lanes.
/// The light tree makes it once per choice rather than once per wide node (a tenth of light_importance4's work).
struct ImportancePoint4 {
  simd4::F px, py, pz;           // p
  simd4::F nx, ny, nz;           // the normal
  simd4::F abs_nx, abs_ny, abs_nz;  // |normal|, per component
  bool oriented;                 // a normal was given (not the zero vector)
  ImportancePoint4(Vec3 p, Vec3 normal)
      : px(_mm_set1_ps(p.x)), py(_mm_set1_ps(p.y)), pz(_mm_set1_ps(p.z)), nx(_mm_set1_ps(normal.x)),
        ny(_mm_set1_ps(normal.y)), nz(_mm_set1_ps(normal.z)), abs_nx(_mm_set1_ps(std::fabs(normal.x))),
        abs_ny(_mm_set1_ps(std::fabs(normal.y))), abs_nz(_mm_set1_ps(std::fabs(normal.z))),
        oriented(!(normal == Vec3{})) {}
};

/// The importance of each lane's bounds at (p, normal), and the certificate. Inline: the tree's split calls it once
/// per wide node, and the call's own stores and loads were a tenth of its cost.
inline Importance4 light_importance4(const ImportanceBounds4& b, const ImportancePoint4& at) {
  using namespace simd4;
  const F zero = _mm_setzero_ps(), one = splat(1.0f), floor = splat(kImportanceCosineFloor);
  const F sign = splat(-0.0f);
  const F intensity = load(b.intensity_w_sr);
  F valid = _mm_cmpgt_ps(intensity, zero);

  const F tx = sub(at.px, load(b.centre_x)), ty = sub(at.py, load(b.centre_y)), tz = sub(at.pz, load(b.centre_z));
  const bool oriented = at.oriented;
  const F normal_dot = dot3(at.nx, at.ny, at.nz, tx, ty, tz);
  F above = _mm_castsi128_ps(_mm_set1_epi32(-1));  // the certificate's box strictly above the tangent plane
  if (oriented) {
    // Some of the box above the tangent plane: the scalar −normal_dot + |n|·half > 0.
    const F reach = dot3(at.abs_nx, at.abs_ny, at.abs_nz, load(b.half_x), load(b.half_y), load(b.half_z));
    valid = _mm_and_ps(valid, _mm_cmpgt_ps(add(_mm_xor_ps(normal_dot, sign), reach), zero));
    above = _mm_cmpgt_ps(sub(_mm_xor_ps(normal_dot, sign), reach), zero);
  }
  const F axis_x = load(b.axis_x), axis_y = load(b.axis_y), axis_z = load(b.axis_z);
  const F in_front = _mm_cmpgt_ps(dot3(axis_x, axis_y, axis_z, at.px, at.py, at.pz), load(b.plane_offset_m));
  valid = _mm_andnot_ps(_mm_andnot_ps(in_front, mask(b.half_space)), valid);

  const F smallest = splat(std::numeric_limits<float>::min()), largest = splat(1e30f);
  const F distance2 = dot3(tx, ty, tz, tx, ty, tz);
  const F radius2 = load(b.radius2_m2);
  const F inside = _mm_cmple_ps(distance2, radius2);
  // Inside the bounding sphere: I / r², or 0 at a point light.
  const F inside_value = _mm_movemask_ps(inside) == 0 ? zero
                         : _mm_and_ps(_mm_cmpgt_ps(radius2, zero), clamp(_mm_div_ps(intensity, radius2), smallest, largest));

  const F inverse_distance = _mm_div_ps(one, _mm_sqrt_ps(distance2));
  const F sin_u = min_with(mul(load(b.radius_m), inverse_distance), one);
  const F cos_u = _mm_sqrt_ps(max_with(sub(one, mul(sin_u, sin_u)), zero));

  const F cos_w_signed = mul(dot3(axis_x, axis_y, axis_z, tx, ty, tz), inverse_distance);
  const F cos_w = select(mask(b.two_sided), _mm_andnot_ps(sign, cos_w_signed), cos_w_signed);
  // max(0, θw − θo): (1, 0) inside the cone, else the angle difference.
  const F cos_o = load(b.cos_theta_o), sin_o = load(b.sin_theta_o);
  const F in_cone = _mm_cmpge_ps(cos_w, cos_o);
  const F sin_w = sine_of(cos_w);
  const F beyond_cos = select(in_cone, one, add(mul(cos_w, cos_o), mul(sin_w, sin_o)));
  const F beyond_sin = select(in_cone, zero, sub(mul(sin_w, cos_o), mul(cos_w, sin_o)));
  // Less θu, clamped at 0.
  const F emission_cos =
      select(_mm_cmpge_ps(beyond_cos, cos_u), one, add(mul(beyond_cos, cos_u), mul(beyond_sin, sin_u)));
  const F emits = _mm_cmpge_ps(emission_cos, load(b.cos_theta_e));  // the scalar's !(cos < cos θe)

  F receiver = one;
  if (oriented) {
    const F cos_i = mul(_mm_xor_ps(normal_dot, sign), inverse_distance);
    receiver = select(_mm_cmpge_ps(cos_i, cos_u), one,
                      max_with(add(mul(cos_i, cos_u), mul(sine_of(cos_i), sin_u)), floor));
  }
  const F importance =
      clamp(_mm_div_ps(mul(mul(intensity, max_with(emission_cos, floor)), receiver), distance2), smallest, largest);
  const F outside_value = _mm_and_ps(emits, importance);
  const F value = _mm_and_ps(valid, select(inside, inside_value, outside_value));
  // The certificate: cos and sin of ∠(axis, w) + θu by the angle-sum formula (a sum past π fails: its sine turns
  // negative) against the narrowed lit cone. Two-sided lanes never pass (their threshold is 3), so sin_w, taken of
  // |cos_w| there, is the signed angle's sine wherever it matters.
  const F c_sum = sub(mul(cos_w_signed, cos_u), mul(sin_w, sin_u));
  const F s_sum = add(mul(sin_w, cos_u), mul(cos_w_signed, sin_u));
  F certified = _mm_and_ps(_mm_and_ps(valid, above), _mm_cmpgt_ps(distance2, radius2));
  certified = _mm_and_ps(certified, _mm_cmpge_ps(s_sum, zero));
  certified = _mm_and_ps(certified, _mm_cmpge_ps(c_sum, load(b.certify_threshold)));
  Importance4 out;
  _mm_storeu_ps(out.value.data(), value);
  out.certified = _mm_movemask_ps(certified);
  return out;
}

inline Importance4 light_importance4(const ImportanceBounds4& b, Vec3 p, Vec3 normal) {
  return light_importance4(b, ImportancePoint4(p, normal));
}

/// Bit j set exactly where lane j's light_importance at (p, normal) is > 0, without the importance itself: past the
/// tests that can zero it (the tangent plane, the half-space, p at a point light, the emission cone) the scalar code
/// clamps it to ≥ the smallest normal float, its numerator is finite (a finite intensity times cosines floored at
/// kImportanceCosineFloor) and its denominator the positive squared distance, so it is > 0 there. The same operations
/// as light_importance4 up to that test, less the receiver's cosine, the divisions and the certificate: the light
/// tree checks its slots' representatives with it (tests/transport/light_bounds4_test.cpp checks it against the
/// scalar importance).
inline int light_scores4(const ImportanceBounds4& b, const ImportancePoint4& at) {
  using namespace simd4;
  const F zero = _mm_setzero_ps(), one = splat(1.0f);
  const F sign = splat(-0.0f);
  F valid = _mm_cmpgt_ps(load(b.intensity_w_sr), zero);
  const F tx = sub(at.px, load(b.centre_x)), ty = sub(at.py, load(b.centre_y)), tz = sub(at.pz, load(b.centre_z));
  if (at.oriented) {
    const F normal_dot = dot3(at.nx, at.ny, at.nz, tx, ty, tz);
    const F reach = dot3(at.abs_nx, at.abs_ny, at.abs_nz, load(b.half_x), load(b.half_y), load(b.half_z));
    valid = _mm_and_ps(valid, _mm_cmpgt_ps(add(_mm_xor_ps(normal_dot, sign), reach), zero));
  }
  const F axis_x = load(b.axis_x), axis_y = load(b.axis_y), axis_z = load(b.axis_z);
  const F in_front = _mm_cmpgt_ps(dot3(axis_x, axis_y, axis_z, at.px, at.py, at.pz), load(b.plane_offset_m));
  valid = _mm_andnot_ps(_mm_andnot_ps(in_front, mask(b.half_space)), valid);
  if (_mm_movemask_ps(valid) == 0) return 0;

  const F distance2 = dot3(tx, ty, tz, tx, ty, tz);
  const F radius2 = load(b.radius2_m2);
  const F inside = _mm_cmple_ps(distance2, radius2);
  const F inverse_distance = _mm_div_ps(one, _mm_sqrt_ps(distance2));
  const F sin_u = min_with(mul(load(b.radius_m), inverse_distance), one);
  const F cos_u = _mm_sqrt_ps(max_with(sub(one, mul(sin_u, sin_u)), zero));
  const F cos_w_signed = mul(dot3(axis_x, axis_y, axis_z, tx, ty, tz), inverse_distance);
  const F cos_w = select(mask(b.two_sided), _mm_andnot_ps(sign, cos_w_signed), cos_w_signed);
  const F cos_o = load(b.cos_theta_o), sin_o = load(b.sin_theta_o);
  const F in_cone = _mm_cmpge_ps(cos_w, cos_o);
  const F sin_w = sine_of(cos_w);
  const F beyond_cos = select(in_cone, one, add(mul(cos_w, cos_o), mul(sin_w, sin_o)));
  const F beyond_sin = select(in_cone, zero, sub(mul(sin_w, cos_o), mul(cos_w, sin_o)));
  const F emission_cos =
      select(_mm_cmpge_ps(beyond_cos, cos_u), one, add(mul(beyond_cos, cos_u), mul(beyond_sin, sin_u)));
  const F emits = _mm_cmpge_ps(emission_cos, load(b.cos_theta_e));
  // Inside the bounding sphere: > 0 unless p is at a point light (radius 0).
  const F scores = select(inside, _mm_cmpgt_ps(radius2, zero), emits);
  return _mm_movemask_ps(_mm_and_ps(valid, scores));
}

inline int light_scores4(const ImportanceBounds4& b, Vec3 p, Vec3 normal) {
  return light_scores4(b, ImportancePoint4(p, normal));
}

}  // namespace rimu
