// The SIMD lane type: four floats in one SSE register.
//
// Every path carries kLaneCount wavelengths together (hero + partners). This is the one place where that
// width is set; everything spectral that is evaluated per sample is a Float4 (values) with a Mask4
// (per-lane booleans). Operations are lane-wise unless their name says otherwise (sum, any, all).
#pragma once

#include <smmintrin.h>  // SSE4.1

#include <array>
#include <cmath>
#include <cstdint>

namespace rimu {

inline constexpr int kLaneCount = 4;
/// kLaneCount as a float, for the spectral MIS sums (Σ of kLaneCount pdf ratios).
inline constexpr float kLanes = float(kLaneCount);

/// Four per-lane booleans (all-ones or all-zeros bit patterns in an SSE register).
struct Mask4 {
  __m128 v;

  Mask4() : v(_mm_setzero_ps()) {}
  explicit Mask4(__m128 bits) : v(bits) {}
  explicit Mask4(bool all) : v(_mm_castsi128_ps(_mm_set1_epi32(all ? -1 : 0))) {}

  /// Lane i as a bool.
  bool operator[](int i) const { return (_mm_movemask_ps(v) >> i) & 1; }
  /// Bit i set where lane i is true.
  int bits() const { return _mm_movemask_ps(v); }
  bool any() const { return bits() != 0; }
  bool all() const { return bits() == 0xF; }
  bool none() const { return bits() == 0; }

  friend Mask4 operator&(Mask4 a, Mask4 b) { return Mask4(_mm_and_ps(a.v, b.v)); }
  friend Mask4 operator|(Mask4 a, Mask4 b) { return Mask4(_mm_or_ps(a.v, b.v)); }
  friend Mask4 operator^(Mask4 a, Mask4 b) { return Mask4(_mm_xor_ps(a.v, b.v)); }
  friend Mask4 operator!(Mask4 a) { return Mask4(_mm_xor_ps(a.v, _mm_castsi128_ps(_mm_set1_epi32(-1)))); }
};

/// Four floats, one per lane.
struct Float4 {
  __m128 v;

  Float4() : v(_mm_setzero_ps()) {}
  /// Broadcast: every lane holds `x`.
  Float4(float x) : v(_mm_set1_ps(x)) {}  // NOLINT(google-explicit-constructor): scalars mix freely
  Float4(float a, float b, float c, float d) : v(_mm_setr_ps(a, b, c, d)) {}
  explicit Float4(__m128 x) : v(x) {}
  static Float4 load(const float* p) { return Float4(_mm_loadu_ps(p)); }

  float operator[](int i) const {
    alignas(16) float out[4];
    _mm_store_ps(out, v);
    return out[i];
  }
  /// Sets lane i; not for hot loops (it round-trips through memory).
  void set(int i, float x) {
    alignas(16) float out[4];
    _mm_store_ps(out, v);
    out[i] = x;
    v = _mm_load_ps(out);
  }
  std::array<float, 4> to_array() const {
    std::array<float, 4> out;
    _mm_storeu_ps(out.data(), v);
    return out;
  }

  friend Float4 operator+(Float4 a, Float4 b) { return Float4(_mm_add_ps(a.v, b.v)); }
  friend Float4 operator-(Float4 a, Float4 b) { return Float4(_mm_sub_ps(a.v, b.v)); }
  friend Float4 operator*(Float4 a, Float4 b) { return Float4(_mm_mul_ps(a.v, b.v)); }
  friend Float4 operator/(Float4 a, Float4 b) { return Float4(_mm_div_ps(a.v, b.v)); }
  friend Float4 operator-(Float4 a) { return Float4(_mm_xor_ps(a.v, _mm_set1_ps(-0.0f))); }
  Float4& operator+=(Float4 b) { return *this = *this + b; }
  Float4& operator-=(Float4 b) { return *this = *this - b; }
  Float4& operator*=(Float4 b) { return *this = *this * b; }
  Float4& operator/=(Float4 b) { return *this = *this / b; }

  friend Mask4 operator<(Float4 a, Float4 b) { return Mask4(_mm_cmplt_ps(a.v, b.v)); }
  friend Mask4 operator<=(Float4 a, Float4 b) { return Mask4(_mm_cmple_ps(a.v, b.v)); }
  friend Mask4 operator>(Float4 a, Float4 b) { return Mask4(_mm_cmpgt_ps(a.v, b.v)); }
  friend Mask4 operator>=(Float4 a, Float4 b) { return Mask4(_mm_cmpge_ps(a.v, b.v)); }
  friend Mask4 operator==(Float4 a, Float4 b) { return Mask4(_mm_cmpeq_ps(a.v, b.v)); }
  friend Mask4 operator!=(Float4 a, Float4 b) { return Mask4(_mm_cmpneq_ps(a.v, b.v)); }
};

inline Float4 min(Float4 a, Float4 b) { return Float4(_mm_min_ps(a.v, b.v)); }
inline Float4 max(Float4 a, Float4 b) { return Float4(_mm_max_ps(a.v, b.v)); }
inline Float4 abs(Float4 a) { return Float4(_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)); }
inline Float4 sqrt(Float4 a) { return Float4(_mm_sqrt_ps(a.v)); }
inline Float4 floor(Float4 a) { return Float4(_mm_floor_ps(a.v)); }
inline Float4 clamp(Float4 x, Float4 lo, Float4 hi) { return min(max(x, lo), hi); }
/// Fused form of a*b + c (two instructions without FMA; kept as one call so FMA builds can use it).
inline Float4 mul_add(Float4 a, Float4 b, Float4 c) { return a * b + c; }
/// Lane-wise `mask ? if_true : if_false`.
inline Float4 select(Mask4 mask, Float4 if_true, Float4 if_false) {
  return Float4(_mm_blendv_ps(if_false.v, if_true.v, mask.v));
}
/// Lane-wise exp (scalar per lane: exactness over speed; media use it once per collision).
inline Float4 exp(Float4 a) {
  const auto x = a.to_array();
  return Float4(std::exp(x[0]), std::exp(x[1]), std::exp(x[2]), std::exp(x[3]));
}
/// Horizontal sum of the four lanes.
inline float sum(Float4 a) {
  __m128 shuf = _mm_movehdup_ps(a.v);
  __m128 sums = _mm_add_ps(a.v, shuf);
  shuf = _mm_movehl_ps(shuf, sums);
  return _mm_cvtss_f32(_mm_add_ss(sums, shuf));
}
/// The largest (smallest) lane with std::fmax's (fmin's) rule for NaN: NaN lanes are ignored, and the answer is
/// NaN only if every lane is. In registers: std::fmax is a libm call (SSE's maxps does not ignore NaN), three per
/// lane reduction, and max_lane runs at every step of a medium's tracking. NaN lanes become −∞ (+∞) first, which
/// never wins unless every lane is NaN or that infinity.
inline float max_lane(Float4 a) {
  const __m128 nan = _mm_cmpunord_ps(a.v, a.v);
  if (_mm_movemask_ps(nan) == 0xF) return a[0];
  __m128 v = _mm_blendv_ps(a.v, _mm_set1_ps(-INFINITY), nan);
  v = _mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
  v = _mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2)));
  return _mm_cvtss_f32(v);
}
inline float min_lane(Float4 a) {
  const __m128 nan = _mm_cmpunord_ps(a.v, a.v);
  if (_mm_movemask_ps(nan) == 0xF) return a[0];
  __m128 v = _mm_blendv_ps(a.v, _mm_set1_ps(INFINITY), nan);
  v = _mm_min_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
  v = _mm_min_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2)));
  return _mm_cvtss_f32(v);
}
/// True in lanes holding NaN.
inline Mask4 is_nan(Float4 a) { return Mask4(_mm_cmpunord_ps(a.v, a.v)); }
/// True in lanes holding a finite number (neither NaN nor +-Inf).
inline Mask4 is_finite(Float4 a) { return abs(a) < Float4(INFINITY); }

}  // namespace rimu
