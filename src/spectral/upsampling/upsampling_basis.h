// The fast path of RGB upsampling: smoothest spectra as a few coefficients of a fixed basis, precomputed at the
// table's grid points and interpolated, so an upsampled colour costs 3×3 solves instead of the exact path's
// 95-knot colour correction, and a texel stores 16 floats instead of 95.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>
#include <immintrin.h>

#include "spectral/wavelengths/lanes.h"
#include "spectral/upsampling/upsampling_table.h"

namespace rimu {

struct Matrix3;

/// Number of basis functions: the 4 that span every smoothest spectrum with no zero knot (exactly), plus 12
/// principal components of what the table's spectra with zero regions add. docs/upsampling.md ("Fast path") has
/// the accuracy against this number; 16 floats = 64 bytes per texel.
inline constexpr int kUpsamplingBasisSize = 16;

/// A spectrum as coefficients of an UpsamplingBasis: S(λ) = Σ_k c_k φ_k(λ). Linear, so blending coefficients
/// (bilinear texture filtering) blends the spectra, and their colours.
struct BasisCoefficients {
  alignas(16) std::array<float, kUpsamplingBasisSize> c{};

  BasisCoefficients& operator*=(float k) {
    for (float& v : c) v *= k;
    return *this;
  }
};

/// What smooth_coefficients knows about the spectrum besides its coefficients, so that callers can skip a
/// 95-knot pass (~50-90 ns) when it cannot matter.
struct SmoothShapeBounds {
  /// The correction directions D (columns X, Y, Z) of the colour at Y = 1: the four corners' D blended with the
  /// bilinear weights, what correction_directions() scales for a fit (a fifth of random sRGB colours need one).
  /// Left uninitialised (the setup's hot path fills it; zeroing 192 bytes per colour showed in its profile).
  alignas(16) float directions[3][kUpsamplingBasisSize];
  float peak_bound = 0;  ///< ≥ the largest knot of Φc (interpolated corner peaks, raised by the correction)
  /// The colour asked for, xyz(xy, Y = 1): what a fit of the clamped spectrum aims at (times the luminance).
  Xyz colour;
  /// True if some corner's spectrum needed clamping (δ ≠ 0, see smooth_coefficients): then only a fit makes the
  /// colour exact.
  bool rings = false;
  /// The 8-knot blocks (bit b: knots 8b .. 8b + 7) where some corner's spectrum dips below a tenth of its peak:
  /// the only knots at which Φc can be negative (fit_zero_clamped's candidates).
  uint32_t low_blocks = 0;
  /// M·D (row-major) at Y = 1: the colour's change per unit step along the directions, fit_zero_clamped's
  /// Jacobian.
  std::array<float, 9> colour_per_direction{};
};

namespace upsampling_kernels {

/// The four lanes' dot products Σ_k c_k·phi[lane][k] (phi: 4 × 16 floats, 32-byte aligned; c: 16 floats). The
/// SSE4.1 build: 16 multiplies, 12 adds, three horizontal adds.
__m128 dot_lanes_sse(const float* phi, const float* c);
/// The same with AVX2 + FMA: per lane, one 8-lane multiply and one fused multiply-add; one reduction for the four
/// lanes. Inline so that a -march build with AVX2 (RIMU_NATIVE) calls it without dispatch.
__attribute__((target("avx2,fma"))) inline __m128 dot_lanes_avx2(const float* phi, const float* c) {
  const __m256 c0 = _mm256_loadu_ps(c), c1 = _mm256_loadu_ps(c + 8);
  __m256 p[4];
  for (int lane = 0; lane < 4; ++lane)
    p[lane] = _mm256_fmadd_ps(c1, _mm256_load_ps(phi + 16 * lane + 8), _mm256_mul_ps(c0, _mm256_load_ps(phi + 16 * lane)));
  // Within each 128-bit half: [Σ lane 0, Σ lane 1, Σ lane 2, Σ lane 3] of that half's k; then the halves summed.
  const __m256 h = _mm256_hadd_ps(_mm256_hadd_ps(p[0], p[1]), _mm256_hadd_ps(p[2], p[3]));
  return _mm_add_ps(_mm256_castps256_ps128(h), _mm256_extractf128_ps(h, 1));
}
/// dot_lanes of Σ_j weight[j]·corner[j] (j < 4), the blend kept in registers.
__m128 blend_dot_lanes_sse(const float* phi, const BasisCoefficients* const corner[4], const float weight[4]);
__attribute__((target("avx2,fma"))) inline __m128 blend_dot_lanes_avx2(const float* phi,
                                                                        const BasisCoefficients* const corner[4],
                                                                        const float weight[4]) {
  __m256 c0 = _mm256_mul_ps(_mm256_set1_ps(weight[0]), _mm256_loadu_ps(corner[0]->c.data()));
  __m256 c1 = _mm256_mul_ps(_mm256_set1_ps(weight[0]), _mm256_loadu_ps(corner[0]->c.data() + 8));
  for (int j = 1; j < 4; ++j) {
    const __m256 w = _mm256_set1_ps(weight[j]);
    c0 = _mm256_fmadd_ps(w, _mm256_loadu_ps(corner[j]->c.data()), c0);
    c1 = _mm256_fmadd_ps(w, _mm256_loadu_ps(corner[j]->c.data() + 8), c1);
  }
  __m256 p[4];
  for (int lane = 0; lane < 4; ++lane)
    p[lane] = _mm256_fmadd_ps(c1, _mm256_load_ps(phi + 16 * lane + 8), _mm256_mul_ps(c0, _mm256_load_ps(phi + 16 * lane)));
  const __m256 h = _mm256_hadd_ps(_mm256_hadd_ps(p[0], p[1]), _mm256_hadd_ps(p[2], p[3]));
  return _mm_add_ps(_mm256_castps256_ps128(h), _mm256_extractf128_ps(h, 1));
}

}  // namespace upsampling_kernels

/// The basis, each table entry's coefficients and the colour correction, built from one white's table.
///
/// Basis (orthonormal over the 95 knots, each φ_k a knot spectrum): without active bounds the smoothest spectrum
/// of colour t solves 2LS = −Aᵀμ (L = DᵀD the roughness form, A the knot colorimetry), so it lies in
/// span{1, L⁺a_X, L⁺a_Y, L⁺a_Z} (a_k the rows of A, projected to zero mean): those four come first and represent
/// unsaturated colours exactly. The rest are the principal components of the table's peak-1 shapes after those
/// four are projected out: the zero regions and narrow peaks of saturated colours.
///
/// Colour correction: the interpolated coefficients miss the target XYZ by the table's interpolation error. It is
/// re-imposed as the exact path does (RgbUpsampler, docs/upsampling.md): by the smallest change in the metric
/// Σ ΔS_i²/S_i, ΔS = diag(S)·Aᵀλ, which leaves zero regions at zero, here projected onto the basis:
/// Δc = D·λ with D = Φᵀ·diag(S)·Aᵀ (K×3). D is linear in S, so it is precomputed per table entry (from the exact
/// table spectrum) and interpolated with the same weights; λ solves the 3×3 system (M·D)·λ = t − M·c with
/// M = A·Φ, so the colour is exact up to float rounding. Cost: a 3×K blend and a 3×3 solve, no 95-knot loop.
///
/// Clamping: the truncated basis rings (a few 1e-3 of the peak) around the exact spectrum's zero regions, and a
/// reflectance must stay in [0, 1], so the spectrum used is clamp(Φc, 0, upper) at the knots, linear in between
/// (evaluate_clamped). Clamping moves the colour (by up to 0.3 ΔE00 for dark saturated purples). At each entry the
/// coefficients are fitted so that the clamped spectrum has the entry's colour, and the offset δ = M·c −
/// colour(clamped) is stored and blended, so the correction can aim the unclamped colour at t + δ; between
/// entries that ring, fit_clamped re-imposes the target on the clamped spectrum with the same correction
/// directions, as the exact path repeats its correction while clamping.
class UpsamplingBasis {
 public:
  /// Which builds of the setup and evaluation kernels a basis calls: the best the CPU runs (AVX2 + FMA where
  /// present), or the SSE4.1 baseline everywhere (tests compare the two on one machine).
  enum class Kernels { best_for_cpu, sse41 };

  /// Builds the basis and projects every table entry onto it (~20 ms of CPU; once per colour space).
  UpsamplingBasis(const UpsamplingTable& table, const KnotColorimetry& colorimetry,
                  Kernels kernels = Kernels::best_for_cpu);

  /// Coefficients of the spectrum with chromaticity `xy` and luminance Y = 1 (under the table's white): the four
  /// entries around (θ, ρ) interpolated bilinearly (each Y-normalised, as UpsamplingTable::interpolate), then
  /// colour-corrected so that xyz_of() is xyz(xy, Y = 1) + δ up to float rounding, δ the blended clamping offset
  /// (M·c − colour(clamp(Φc, 0, ∞)) at the entries: what clamping at 0 takes away), so that the spectrum clamped
  /// at 0 lands near xyz(xy, 1) = bounds->colour; exactly there if no corner rings (bounds->rings false),
  /// otherwise a fit (fit_zero_clamped, fit_clamped) finishes the job. `xy` must lie inside the
  /// usable gamut (relative radius ≤ 1: the caller maps it). Allocation-free; ~70 ns.
  BasisCoefficients smooth_coefficients(Chromaticity xy, double angle_rad, double relative_radius,
                                        SmoothShapeBounds* bounds = nullptr) const;

  /// The correction directions D of smooth_coefficients's colour (bounds.directions), times `scale` (the
  /// luminance c was scaled by): fit_clamped's `directions`.
  std::array<BasisCoefficients, 3> correction_directions(const SmoothShapeBounds& bounds, float scale) const;

  /// Moves `c` along `directions` (correction_directions) until clamp(Φc, 0, upper) has colour
  /// `target` (relative 1e-5): quasi-Newton steps, each one 95-knot pass, normally 2 passes.
  /// Returns the residual left, |ΔX| + |ΔY| + |ΔZ| relative to |X| + |Y| + |Z| of the target: above ~1e-4 the
  /// basis cannot hold this colour's spectrum at zero (saturated purples of the wide spaces, emission within
  /// ~10 % of the locus; docs/upsampling.md), and the caller reports the colour as moved.
  /// `first_knots` (optional): Φc already computed (knots_float) for c / first_knots_scale, which saves the first
  /// pass.
  double fit_clamped(BasisCoefficients& c, const std::array<BasisCoefficients, 3>& directions, const Xyz& target,
                     float upper, const float* first_knots = nullptr, float first_knots_scale = 1.0f) const;

  /// fit_clamped for a spectrum expected to clamp only at zero (emission with `upper` = ∞; a reflectance whose
  /// peak is at most `upper` = 1 before the fit), from smooth_coefficients's `bounds` with c and the directions
  /// scaled by `scale`: a pass computes Φc only in bounds.low_blocks (the colour of clamp(Φc, 0, ∞) is M·c minus
  /// the negative knots' colour), and the Jacobian is scale·M·D from the interpolated entries, so a pass costs
  /// about a quarter of fit_clamped's. The result is verified with one 95-knot pass: if a knot outside the low
  /// blocks is negative or one exceeds `upper` (a fit can raise a peak by a few per cent), or the fit did not
  /// converge, fit_clamped continues from there (reusing that pass). Same stopping rule and return value.
  double fit_zero_clamped(BasisCoefficients& c, const SmoothShapeBounds& bounds, float scale, const Xyz& target,
                          float upper) const;

  /// The knots' blocks of 8 (bit b: knots 8b .. 8b + 7) where Φc < 0 (tests: low_blocks must contain them).
  uint32_t negative_blocks(const BasisCoefficients& c) const;

  /// Where a chromaticity at offset (dx, dy) from the white lies, without an atan2: `angle_cell` = θ·angle_count/2π
  /// in [0, angle_count] (θ ∈ [0, 2π)) and `inverse_usable_radius` = 1/(R(θ)·usable_fraction), both interpolated
  /// linearly in a 2048-step table (16 KB) over the pseudo-angle p = 1 − dx/(|dx|+|dy|) (dy ≥ 0) or
  /// 3 + dx/(|dx|+|dy|) (dy < 0), which is monotonic in θ. θ(p) is smooth (|θ''| ≤ 2), so the table's θ is within
  /// 1e-6 rad of atan2's (h²/8·|θ''|, h = 4/2048). The reciprocal is tabulated so that ρ = |offset|·(1/R) is a
  /// product, not a second division on the setup's critical path. Along a straight hull edge 1/R(θ) = cos(θ − φ)/d
  /// is concave, so the lerp's chord understates it by ≤ (2h)²/8 ≈ 2e-6 relative (dθ/dp ≤ 2), i.e. R by as much
  /// above the hull; at a hull vertex 1/R has a kink upwards and the lerp overstates it by ≤ 2e-3 (tested;
  /// usable_radius's finer table: ≤ 1e-3), so a colour within 0.2 % of the usable edge may be moved onto it.
  /// Cost: one division and one 16-byte load.
  struct PolarCell {
    double angle_cell = 0;
    double inverse_usable_radius = 0;
    double usable_radius() const { return 1.0 / inverse_usable_radius; }
  };
  PolarCell locate(double dx, double dy) const {
    const double sum = std::abs(dx) + std::abs(dy);
    const double q = sum > 0.0 ? dx / sum : 1.0;
    const double p = dy >= 0.0 ? 1.0 - q : 3.0 + q;
    const double x = std::min(p * (kPseudoAngleSteps / 4.0), double(kPseudoAngleSteps));
    const int i = std::min(int(x), kPseudoAngleSteps - 1);
    const double t = x - i;
    const float* row = &pseudo_angle_table_[size_t(i) * 2];  // angle_cell, 1/radius at i, then at i + 1
    return {row[0] + t * (row[2] - row[0]), row[1] + t * (row[3] - row[1])};
  }

  /// smooth_coefficients with the angle as locate()'s cell coordinate (the fast path's own entry point).
  BasisCoefficients smooth_coefficients_in_cell(Chromaticity xy, double angle_cell, double relative_radius,
                                                SmoothShapeBounds* bounds = nullptr) const;

  /// R(θ)·usable_fraction: distance from the white to the usable gamut's edge (RgbUpsampler's ρ = 1), linear
  /// interpolation in a 4096-step table (≤ 1e-3 relative to the hull's exact radius, at the hull's vertices; the
  /// error only moves which smooth shape is chosen and where the radial gamut move starts, by ≤ 0.1 % of the
  /// radius, still inside the hull; the colour is corrected regardless).
  double usable_radius(double angle_rad) const;

  /// The spectrum clamp(Φc, lower, upper) at four wavelengths (4-lane, allocation-free): the clamped knot values
  /// interpolated linearly in wavelength, so it equals KnotSamples of the clamped knots up to float rounding, and
  /// its colour is the knot colorimetry's (what the fit made exact). Constant beyond 360 and 830 nm. Pass
  /// ±infinity for no clamping. ~16 ns: two 16-term dot products per lane. The reference for evaluate().
  Float4 evaluate_clamped(const BasisCoefficients& c, Float4 lambda_nm, Float4 lower, Float4 upper) const {
    const Float4 x = clamp((lambda_nm - Float4(float(kUpsampleFirstKnotNm))) * Float4(float(1.0 / kUpsampleKnotSpacingNm)),
                           Float4(0.0f), Float4(float(kUpsampleKnotCount - 1)));
    const Float4 base = floor(x);
    const Float4 t = x - base;
    const __m128i index = _mm_cvttps_epi32(base.v);
    const int lane_index[4] = {_mm_cvtsi128_si32(index), _mm_extract_epi32(index, 1), _mm_extract_epi32(index, 2),
                               _mm_extract_epi32(index, 3)};
    // Per lane: the dot products of c with the basis rows at the knot below and above, summed across the
    // register by a 4×4 transpose, clamped, then linear interpolation in wavelength.
    __m128 lo[4], hi[4];
    for (int lane = 0; lane < 4; ++lane) {
      const float* row = &rows_[size_t(lane_index[lane]) * kUpsamplingBasisSize];
      __m128 a = _mm_setzero_ps(), b = _mm_setzero_ps();
      for (int k = 0; k < kUpsamplingBasisSize; k += 4) {
        const __m128 ck = _mm_load_ps(&c.c[k]);
        a = _mm_add_ps(a, _mm_mul_ps(ck, _mm_loadu_ps(row + k)));
        b = _mm_add_ps(b, _mm_mul_ps(ck, _mm_loadu_ps(row + kUpsamplingBasisSize + k)));
      }
      lo[lane] = a, hi[lane] = b;
    }
    _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
    _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
    const Float4 v0 = clamp(Float4(_mm_add_ps(_mm_add_ps(lo[0], lo[1]), _mm_add_ps(lo[2], lo[3]))), lower, upper);
    const Float4 v1 = clamp(Float4(_mm_add_ps(_mm_add_ps(hi[0], hi[1]), _mm_add_ps(hi[2], hi[3]))), lower, upper);
    return mul_add(t, v1 - v0, v0);
  }

  /// The rendering evaluation: clamp(Φ(λ)·c, lower, upper), Φ(λ) the basis interpolated linearly between knots.
  /// It equals evaluate_clamped wherever the two knots around a wavelength are both inside [lower, upper]; where
  /// the spectrum crosses a bound between two knots (the ringing around zero regions, narrow peaks at 1) it
  /// clamps after interpolating instead of before, which moves the colour by ΔE00 ≤ ~1e-2 (docs/upsampling.md,
  /// "Fast path"). The interpolated basis Φ(λ) comes from a per-thread cache (at()) filled once per wavelength set,
  /// so an evaluation is one 16-term dot product per lane: with AVX2 + FMA (chosen once per basis, by the CPU)
  /// two 8-lane fused multiply-adds per lane and one horizontal reduction (~3-5 ns), else SSE4.1.
  Float4 evaluate(const BasisCoefficients& c, Float4 lambda_nm, Float4 lower, Float4 upper) const {
    const BasisAtWavelengths& b = at(lambda_nm);
#if defined(__AVX2__) && defined(__FMA__)
    return clamp(Float4(upsampling_kernels::dot_lanes_avx2(b.phi[0], c.c.data())), lower, upper);
#else
    return clamp(Float4(dot_lanes_(b.phi[0], c.c.data())), lower, upper);
#endif
  }

  /// evaluate() of the blend Σ_j weight[j]·corner[j] (j < 4; a bilinear texture lookup's four texels) without
  /// forming the blend in memory: one dispatched call for the blend and the dot products (8-lane FMA with AVX2).
  Float4 evaluate_blend(const BasisCoefficients* const corner[4], const float weight[4], Float4 lambda_nm,
                        Float4 lower, Float4 upper) const {
    const BasisAtWavelengths& b = at(lambda_nm);
#if defined(__AVX2__) && defined(__FMA__)
    return clamp(Float4(upsampling_kernels::blend_dot_lanes_avx2(b.phi[0], corner, weight)), lower, upper);
#else
    return clamp(Float4(blend_dot_lanes_(b.phi[0], corner, weight)), lower, upper);
#endif
  }

  /// The basis interpolated at four wavelengths: phi[lane][k] = φ_k(λ_lane). 288 bytes.
  struct BasisAtWavelengths {
    uint64_t basis_id;  // UpsamplingBasis::id_ of the basis it holds; 0: empty
    alignas(16) float lambda_nm[4];
    alignas(32) float phi[4][kUpsamplingBasisSize];
  };
  /// This basis at `lambda_nm`, from the calling thread's one-entry cache, refilled (a few ns) when the basis or
  /// any wavelength differs from the last call's: a path evaluates every texture it meets at its same four
  /// wavelengths. Valid until the thread's next at().
  const BasisAtWavelengths& at(Float4 lambda_nm) const {
    BasisAtWavelengths& cache = thread_cache_;
    if (cache.basis_id != id_ ||
        _mm_movemask_ps(_mm_cmpeq_ps(lambda_nm.v, _mm_load_ps(cache.lambda_nm))) != 0xF) [[unlikely]]
      fill(cache, lambda_nm);
    return cache;
  }

  /// The knot values Φ·c (double, for setup and colorimetry).
  KnotValues knots(const BasisCoefficients& c) const;
  /// Φ·c at the 95 knots in float (~50-90 ns: the AVX2 or the SSE build of the loop, chosen by the CPU) into
  /// `out` (96 floats, the last a pad); returns the largest value (the brightness limit's input) and, if asked,
  /// the 8-knot blocks holding a negative value (bit b: knots 8b .. 8b + 7).
  float knots_float(const BasisCoefficients& c, float* out, uint32_t* negative_blocks = nullptr) const;
  /// XYZ (Y(white) = 1) of the unclamped spectrum: M·c.
  Xyz xyz_of(const BasisCoefficients& c) const;
  /// Basis function k at knot i.
  double basis(int k, int i) const { return rows_[size_t(i) * kUpsamplingBasisSize + k]; }

 private:
  int angle_count_ = 0, radius_count_ = 0;
  std::vector<double> radius_rows_;       // ρ of each table row
  std::vector<double> row_inverse_spacing_;  // 1 / (ρ_{r+1} − ρ_r)
  double angle_scale_ = 0;                // angle_count / 2π: cells per radian
  std::vector<float> rows_;               // (95 + 1 pad) × K, knot-major, 16-byte aligned rows
  // Per table entry, one 320-byte block (five cache lines): first what smooth_coefficients interpolates before
  // anything else (M·c (3), M·D (9, row-major), the peak of the knots of Φc (Y = 1), the clamping offset δ (3)),
  // then the Y = 1 spectrum's coefficients, then its three correction directions D (columns X, Y, Z). Every
  // setup blends all five lines of its four corners (blend_corners_*), the summary first.
  struct Entry {
    alignas(64) std::array<float, 16> summary{};
    std::array<BasisCoefficients, 4> parts;
  };
  std::vector<Entry> entries_;
  // Per entry, its Y = 1 spectrum's 8-knot blocks below a tenth of its peak (SmoothShapeBounds::low_blocks).
  std::vector<uint16_t> low_blocks_;
  bool avx2_fma_ = false;  // the CPU has AVX2 and FMA: smooth_coefficients blends with 8-lane fused multiply-adds
  // evaluate()'s and evaluate_blend()'s kernels, chosen once by the CPU (upsampling_kernels).
  __m128 (*dot_lanes_)(const float*, const float*) = upsampling_kernels::dot_lanes_sse;
  __m128 (*blend_dot_lanes_)(const float*, const BasisCoefficients* const[4], const float[4]) =
      upsampling_kernels::blend_dot_lanes_sse;
  std::array<double, 3> largest_row_{};  // max_i |a_m,i|: bounds the correction's relative change of a knot
  std::array<std::array<double, kUpsamplingBasisSize>, 3> xyz_rows_{};  // M = A Φ
  std::vector<float> colorimetry_rows_;  // A in float, 3 × 96 (pad 0): XYZ of clamped knots
  std::vector<float> columns_;            // K × 96, basis-major: four knots of one basis function per load
  std::vector<float> usable_radius_;      // R(θ)·usable_fraction at 4096 + 1 angles over [−π, π]
  static constexpr int kPseudoAngleSteps = 2048;
  std::vector<float> pseudo_angle_table_;  // (angle_cell, 1/usable radius) at 2048 + 1 pseudo-angles over [0, 4]

  // Unique per constructed basis (a copy shares its id and its rows), so the cache cannot confuse a destroyed basis
  // with a new one built at the same address.
  uint64_t id_ = 0;
  void fill(BasisAtWavelengths& cache, Float4 lambda_nm) const;
  // fit_clamped's pass without AVX2: knots_float (or given × given_scale), then the clamped colour and J's sums.
  void clamped_pass_sse(const BasisCoefficients& c, const float* given, float given_scale, const float* const a[3],
                        float upper, float* out) const;
  // Newton's method on the clamped colour, shared by the two fits: `pass(c, step, sums)` fills the clamped
  // colour (sums[0..2]) and, unless `fixed_inverse` is given, J's six sums (sums[3..8]).
  template <class Pass>
  double newton_fit(BasisCoefficients& c, const std::array<BasisCoefficients, 3>& directions, const Xyz& target,
                    const Pass& pass, const Matrix3* fixed_inverse, int max_steps) const;
  // Trivially constructible and destructible, so access needs no initialisation guard.
  static inline thread_local BasisAtWavelengths thread_cache_{};
};

}  // namespace rimu
