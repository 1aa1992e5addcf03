#include "spectral/upsampling/upsampling_basis.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <numbers>

#include <immintrin.h>

#include "spectral/colour_spaces/matrix3.h"

namespace rimu {
namespace {

constexpr int n = kUpsampleKnotCount;
constexpr int K = kUpsamplingBasisSize;
constexpr int kInteriorSize = 4;  // 1, L⁺a_X, L⁺a_Y, L⁺a_Z
constexpr int kRadiusSteps = 4096;
// fit_clamped stops at this relative XYZ residual (|ΔX| + |ΔY| + |ΔZ| over |X| + |Y| + |Z|): ΔE00 ≲ 1e-3 for
// any colour, below the 0.01 mean the fast path aims at; 1e-6 cost 2.6 passes per fit on random sRGB colours,
// 1e-5 costs 2.1 (docs/upsampling.md "Fast path").
constexpr double kFitTolerance = 1e-5;
// A knot block is a candidate for clamping at zero (low_blocks) where an entry's Y = 1 spectrum dips below this
// fraction of its peak. Between entries a knot is a weighted mean of the corners' values plus the correction,
// which changes it by a few per cent of itself (bounded by SmoothShapeBounds's `change`), and the basis rings by
// ≤ 1e-2 of the peak: a knot at a tenth of the peak in every corner cannot reach zero. The blocks are used only
// while the correction's relative change stays below kMaxLowChange (and fit_zero_clamped verifies its result).
constexpr double kLowFraction = 0.1;
constexpr double kMaxLowChange = 0.5;
// Passes fit_zero_clamped makes before handing over to fit_clamped (random sRGB colours need 1-2).
constexpr int kZeroOnlySteps = 4;
constexpr uint32_t kAllBlocks = (1u << ((n + 7) / 8)) - 1;

using Vector = std::array<double, n>;

// Four partial sums: one running sum is bound by the add latency (the basis's construction is mostly dot products
// of 95 doubles), four let the adds overlap.
double dot(const Vector& a, const Vector& b) {
  double s[4] = {0, 0, 0, 0};
  int i = 0;
  for (; i + 4 <= n; i += 4)
    for (int j = 0; j < 4; ++j) s[j] += a[i + j] * b[i + j];
  for (; i < n; ++i) s[0] += a[i] * b[i];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

/// x = L⁺b for the roughness form L = DᵀD (D: first differences) and a zero-sum b: Dᵀy = b gives
/// y_i = −Σ_{j≤i} b_j, then x is the running sum of y (up to a constant, which the flat basis function holds).
Vector pseudo_inverse_laplacian(const Vector& b) {
  Vector x{};
  double y = 0;
  for (int i = 0; i + 1 < n; ++i) {
    y -= b[i];
    x[i + 1] = x[i] + y;
  }
  return x;
}

/// Removes from `v` its components along `basis[0..count)` (orthonormal), twice for rounding; false if nothing
/// independent is left.
bool orthonormalise(Vector& v, const std::vector<Vector>& basis) {
  const double before = std::sqrt(dot(v, v));
  for (int pass = 0; pass < 2; ++pass)
    for (const Vector& b : basis) {
      const double p = dot(v, b);
      for (int i = 0; i < n; ++i) v[i] -= p * b[i];
    }
  const double norm = std::sqrt(dot(v, v));
  if (!(norm > 1e-9 * before)) return false;
  for (double& x : v) x /= norm;
  return true;
}

/// Eigenvectors of the symmetric n×n matrix `a` (destroyed) by cyclic Jacobi rotations, sorted by decreasing
/// eigenvalue. Dense and O(n³) per sweep: fine once per colour space at n = 95.
std::vector<Vector> eigenvectors_descending(std::vector<double>& a) {
  std::vector<double> v(size_t(n) * n, 0.0);
  for (int i = 0; i < n; ++i) v[size_t(i) * n + i] = 1.0;
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0, diag = 0;
    for (int p = 0; p < n; ++p) {
      diag += a[size_t(p) * n + p] * a[size_t(p) * n + p];
      for (int q = p + 1; q < n; ++q) off += a[size_t(p) * n + q] * a[size_t(p) * n + q];
    }
    if (off <= 1e-26 * diag) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = a[size_t(p) * n + q];
        if (std::abs(apq) < 1e-300) continue;
        const double app = a[size_t(p) * n + p], aqq = a[size_t(q) * n + q];
        const double theta = (aqq - app) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < n; ++k) {  // columns p and q
          const double akp = a[size_t(k) * n + p], akq = a[size_t(k) * n + q];
          a[size_t(k) * n + p] = c * akp - s * akq;
          a[size_t(k) * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {  // rows p and q
          const double apk = a[size_t(p) * n + k], aqk = a[size_t(q) * n + k];
          a[size_t(p) * n + k] = c * apk - s * aqk;
          a[size_t(q) * n + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {
          const double vkp = v[size_t(k) * n + p], vkq = v[size_t(k) * n + q];
          v[size_t(k) * n + p] = c * vkp - s * vkq;
          v[size_t(k) * n + q] = s * vkp + c * vkq;
        }
      }
  }
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int x, int y) { return a[size_t(x) * n + x] > a[size_t(y) * n + y]; });
  std::vector<Vector> out;
  for (int j : order) {
    Vector e;
    for (int i = 0; i < n; ++i) e[i] = v[size_t(i) * n + j];
    out.push_back(e);
  }
  return out;
}

}  // namespace

namespace upsampling_kernels {

__m128 dot_lanes_sse(const float* phi, const float* c) {
  const __m128 c0 = _mm_loadu_ps(c), c1 = _mm_loadu_ps(c + 4), c2 = _mm_loadu_ps(c + 8), c3 = _mm_loadu_ps(c + 12);
  __m128 lane[4];
  for (int l = 0; l < 4; ++l) {
    const float* p = phi + 16 * l;
    lane[l] = _mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, _mm_load_ps(p)), _mm_mul_ps(c1, _mm_load_ps(p + 4))),
                         _mm_add_ps(_mm_mul_ps(c2, _mm_load_ps(p + 8)), _mm_mul_ps(c3, _mm_load_ps(p + 12))));
  }
  return _mm_hadd_ps(_mm_hadd_ps(lane[0], lane[1]), _mm_hadd_ps(lane[2], lane[3]));
}

__m128 blend_dot_lanes_sse(const float* phi, const BasisCoefficients* const corner[4], const float weight[4]) {
  alignas(16) float blend[K];
  for (int k = 0; k < K; k += 4) {
    __m128 s = _mm_mul_ps(_mm_set1_ps(weight[0]), _mm_loadu_ps(&corner[0]->c[k]));
    for (int j = 1; j < 4; ++j) s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(weight[j]), _mm_loadu_ps(&corner[j]->c[k])));
    _mm_store_ps(blend + k, s);
  }
  return dot_lanes_sse(phi, blend);
}

}  // namespace upsampling_kernels

UpsamplingBasis::UpsamplingBasis(const UpsamplingTable& table, const KnotColorimetry& colorimetry, Kernels kernels)
    : angle_count_(table.angle_count), radius_count_(table.radius_count) {
  static std::atomic<uint64_t> next_id{1};
  id_ = next_id.fetch_add(1);
  for (int r = 0; r < radius_count_; ++r) radius_rows_.push_back(table.radius_of_row(r));
  for (int r = 0; r + 1 < radius_count_; ++r) row_inverse_spacing_.push_back(1.0 / (radius_rows_[r + 1] - radius_rows_[r]));
  angle_scale_ = angle_count_ / (2 * std::numbers::pi);
  avx2_fma_ = kernels == Kernels::best_for_cpu && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (avx2_fma_) {
    dot_lanes_ = upsampling_kernels::dot_lanes_avx2;
    blend_dot_lanes_ = upsampling_kernels::blend_dot_lanes_avx2;
  }
  Vector a[3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < n; ++i) a[k][i] = colorimetry.row(k)[i];

  // The interior family: 1 and L⁺(a_k − mean a_k).
  std::vector<Vector> basis;
  Vector flat;
  flat.fill(1.0);
  Vector interior[kInteriorSize] = {flat};
  for (int k = 0; k < 3; ++k) {
    Vector b = a[k];
    double mean = 0;
    for (double v : b) mean += v / n;
    for (double& v : b) v -= mean;
    interior[k + 1] = pseudo_inverse_laplacian(b);
  }
  for (Vector v : interior) {
    [[maybe_unused]] const bool independent = orthonormalise(v, basis);
    assert(independent);
    basis.push_back(v);
  }

  // The rest: principal components of the peak-1 shapes once the interior family is projected out.
  const size_t entries = size_t(table.angle_count) * table.radius_count;
  std::vector<double> covariance(size_t(n) * n, 0.0);
  std::vector<Vector> shapes(entries);
  for (size_t e = 0; e < entries; ++e) {
    for (int i = 0; i < n; ++i) shapes[e][i] = table.shapes[e * n + i] / 65535.0;
    Vector residual = shapes[e];
    for (const Vector& b : basis) {
      const double p = dot(residual, b);
      for (int i = 0; i < n; ++i) residual[i] -= p * b[i];
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j <= i; ++j) covariance[size_t(i) * n + j] += residual[i] * residual[j];
  }
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) covariance[size_t(i) * n + j] = covariance[size_t(j) * n + i];
  for (Vector v : eigenvectors_descending(covariance)) {
    if (int(basis.size()) == K) break;
    if (orthonormalise(v, basis)) basis.push_back(v);
  }
  assert(int(basis.size()) == K);

  rows_.assign(size_t(n + 1) * K, 0.0f);
  columns_.assign(size_t(K) * (n + 1), 0.0f);
  for (int k = 0; k < K; ++k)
    for (int i = 0; i <= n; ++i) {
      const float v = float(basis[k][std::min(i, n - 1)]);
      rows_[size_t(i) * K + k] = v;
      columns_[size_t(k) * (n + 1) + i] = v;
    }
  for (int k = 0; k < K; ++k)
    for (int c = 0; c < 3; ++c) xyz_rows_[c][k] = dot(a[c], basis[k]);
  entries_.resize(entries);
  for (size_t e = 0; e < entries; ++e) {
    Vector s = shapes[e];
    for (double& v : s) v /= table.luminance_limits[e];  // Y = 1
    Vector weighted[3];  // diag(S) a_m
    for (int m = 0; m < 3; ++m)
      for (int i = 0; i < n; ++i) weighted[m][i] = s[i] * a[m][i];
    for (int k = 0; k < K; ++k) {
      entries_[e].parts[0].c[k] = float(dot(s, basis[k]));
      for (int m = 0; m < 3; ++m) entries_[e].parts[m + 1].c[k] = float(dot(basis[k], weighted[m]));  // D = Φᵀ diag(S) Aᵀ
    }
  }
  // Clamping at zero moves the colour of spectra that ring around a zero region. At each entry the coefficients
  // are fitted so that the clamped spectrum has the entry's colour, and the offset δ = M·c − colour(clamped) is
  // kept: interpolated, it lets smooth_coefficients aim the unclamped colour at t + δ, so that the clamped one
  // lands on t without a 95-knot pass (docs/upsampling.md "Fast path").
  colorimetry_rows_.assign(3 * size_t(n + 1), 0.0f);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < n; ++i) colorimetry_rows_[size_t(c) * (n + 1) + i] = float(a[c][i]);
  for (size_t e = 0; e < entries; ++e) {
    const Xyz target = xyz_of(entries_[e].parts[0]);
    fit_clamped(entries_[e].parts[0], {entries_[e].parts[1], entries_[e].parts[2], entries_[e].parts[3]}, target, INFINITY);
    const Xyz fitted = xyz_of(entries_[e].parts[0]);
    entries_[e].summary[13] = float(fitted.x - target.x), entries_[e].summary[14] = float(fitted.y - target.y),
    entries_[e].summary[15] = float(fitted.z - target.z);
  }
  for (size_t e = 0; e < entries; ++e) {
    std::array<float, 16>& v = entries_[e].summary;
    for (int part = 0; part < 4; ++part) {
      const Xyz x = xyz_of(entries_[e].parts[part]);
      if (part == 0) v[0] = float(x.x), v[1] = float(x.y), v[2] = float(x.z);
      else v[3 + 0 * 3 + (part - 1)] = float(x.x), v[3 + 1 * 3 + (part - 1)] = float(x.y), v[3 + 2 * 3 + (part - 1)] = float(x.z);
    }
    const KnotValues knots_e = knots(entries_[e].parts[0]);
    v[12] = float(*std::max_element(knots_e.begin(), knots_e.end()));
  }
  low_blocks_.resize(entries);
  for (size_t e = 0; e < entries; ++e) {
    const KnotValues knots_e = knots(entries_[e].parts[0]);
    const double threshold = kLowFraction * entries_[e].summary[12];
    for (int i = 0; i < n; ++i)
      if (knots_e[i] < threshold) low_blocks_[e] |= uint16_t(1u << (i / 8));
  }
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i < n; ++i) largest_row_[m] = std::max(largest_row_[m], std::abs(a[m][i]));

  const KnotGamut gamut = table.gamut();
  usable_radius_.resize(kRadiusSteps + 1);
  for (int s = 0; s <= kRadiusSteps; ++s)
    usable_radius_[s] =
        float(gamut.boundary_radius(-std::numbers::pi + 2 * std::numbers::pi * s / kRadiusSteps) * table.usable_fraction);
  pseudo_angle_table_.resize(2 * size_t(kPseudoAngleSteps + 1));
  for (int s = 0; s <= kPseudoAngleSteps; ++s) {
    // Invert locate()'s pseudo-angle: p ∈ [0, 2] is dy ≥ 0 with q = dx/(|dx|+|dy|) = 1 − p, p ∈ [2, 4] is dy < 0
    // with q = p − 3; then (dx, dy) = (q, ±(1 − |q|)) up to scale.
    const double p = 4.0 * s / kPseudoAngleSteps;
    const double q = p <= 2.0 ? 1.0 - p : p - 3.0;
    const double theta = std::atan2(p <= 2.0 ? 1.0 - std::abs(q) : -(1.0 - std::abs(q)), q);  // (−π, π]
    const double theta_0_2pi = s == kPseudoAngleSteps ? 2 * std::numbers::pi
                               : theta < 0.0           ? theta + 2 * std::numbers::pi
                                                       : theta;
    pseudo_angle_table_[2 * size_t(s)] = float(theta_0_2pi * angle_scale_);
    pseudo_angle_table_[2 * size_t(s) + 1] = float(1.0 / (gamut.boundary_radius(theta) * table.usable_fraction));
  }
}

double UpsamplingBasis::usable_radius(double angle_rad) const {
  constexpr double kStepsPerRadian = kRadiusSteps / (2 * std::numbers::pi);
  const double x = std::clamp((angle_rad + std::numbers::pi) * kStepsPerRadian, 0.0, double(kRadiusSteps));
  const int i = std::min(int(x), kRadiusSteps - 1);
  const double t = x - i;
  return usable_radius_[i] + t * (usable_radius_[i + 1] - usable_radius_[i]);
}

namespace {

// The bilinear blend of the four corner entries, Σ_c weight[c]·x_c, of everything smooth_coefficients needs: the
// summaries (16 floats each: M·c, M·D, peak, δ) into `summary`, the coefficients (corner[c][0..15]) into
// `coefficients` and the correction directions D (corner[c][16p .. 16p + 15], p = 1..3) into `directions`. None
// of it waits for the 3×3 solve, which needs the blended summary; the coefficients and directions are blended
// while the solve's divisions run, and the correction is then three multiply-adds. Two builds, chosen once per
// basis by the CPU: 8-lane fused multiply-adds (ten independent chains of four) and the SSE4.1 baseline.
__attribute__((target("avx2,fma"))) void blend_corners_avx2(const float* const summary_in[4],
                                                            const float* const corner[4], const float weight[4],
                                                            float* summary, float* coefficients,
                                                            float directions[3][K]) {
  const __m256 w[4] = {_mm256_set1_ps(weight[0]), _mm256_set1_ps(weight[1]), _mm256_set1_ps(weight[2]),
                       _mm256_set1_ps(weight[3])};
  for (int p = -1; p < 4; ++p) {
    const auto source = [&](int c) { return p < 0 ? summary_in[c] : corner[c] + 16 * p; };
    __m256 lo = _mm256_mul_ps(w[0], _mm256_loadu_ps(source(0)));
    __m256 hi = _mm256_mul_ps(w[0], _mm256_loadu_ps(source(0) + 8));
    for (int c = 1; c < 4; ++c) {
      lo = _mm256_fmadd_ps(w[c], _mm256_loadu_ps(source(c)), lo);
      hi = _mm256_fmadd_ps(w[c], _mm256_loadu_ps(source(c) + 8), hi);
    }
    float* out = p < 0 ? summary : p == 0 ? coefficients : directions[p - 1];
    _mm256_storeu_ps(out, lo);
    _mm256_storeu_ps(out + 8, hi);
  }
}

void blend_corners_sse(const float* const summary_in[4], const float* const corner[4], const float weight[4],
                       float* summary, float* coefficients, float directions[3][K]) {
  for (int p = -1; p < 4; ++p) {
    const auto source = [&](int c) { return p < 0 ? summary_in[c] : corner[c] + 16 * p; };
    float* out = p < 0 ? summary : p == 0 ? coefficients : directions[p - 1];
    for (int k = 0; k < K; k += 4) {
      __m128 s = _mm_mul_ps(_mm_set1_ps(weight[0]), _mm_loadu_ps(source(0) + k));
      for (int c = 1; c < 4; ++c) s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(weight[c]), _mm_loadu_ps(source(c) + k)));
      _mm_storeu_ps(out + k, s);
    }
  }
}

// One pass of fit_clamped, fused for AVX2 + FMA: the 96 knot values v = Φc (or given × given_scale) in twelve
// 8-lane registers, then out[0..2] = XYZ of clamp(v, 0, upper) and out[3..8] = J_xx, J_xy, J_xz, J_yy, J_yz, J_zz
// summed over the live knots (inside (0, upper)), as clamped_pass_sse. `a`: the three colorimetry rows, 96 apart.
__attribute__((target("avx2,fma"))) void clamped_pass_avx2(const float* columns, const float* c, const float* given,
                                                           float given_scale, const float* a, float upper,
                                                           float* out) {
  constexpr int kBlocks = (n + 1) / 8;
  __m256 v[kBlocks];
  if (given) {
    const __m256 scale = _mm256_set1_ps(given_scale);
    for (int b = 0; b < kBlocks; ++b) v[b] = _mm256_mul_ps(_mm256_loadu_ps(given + 8 * b), scale);
  } else {
    for (int b = 0; b < kBlocks; ++b) v[b] = _mm256_setzero_ps();
    for (int k = 0; k < K; ++k) {
      const __m256 ck = _mm256_set1_ps(c[k]);
      for (int b = 0; b < kBlocks; ++b) v[b] = _mm256_fmadd_ps(ck, _mm256_loadu_ps(columns + k * (n + 1) + 8 * b), v[b]);
    }
  }
  const __m256 lower_v = _mm256_setzero_ps(), upper_v = _mm256_set1_ps(upper);
  __m256 acc[9];
  for (__m256& x : acc) x = _mm256_setzero_ps();
  for (int b = 0; b < kBlocks; ++b) {
    const __m256 clamped = _mm256_min_ps(_mm256_max_ps(v[b], lower_v), upper_v);
    const __m256 live = _mm256_and_ps(_mm256_cmp_ps(v[b], clamped, _CMP_EQ_OQ), clamped);  // S_i where live
    const __m256 ax = _mm256_loadu_ps(a + 8 * b), ay = _mm256_loadu_ps(a + (n + 1) + 8 * b),
                 az = _mm256_loadu_ps(a + 2 * (n + 1) + 8 * b);
    acc[0] = _mm256_fmadd_ps(clamped, ax, acc[0]);
    acc[1] = _mm256_fmadd_ps(clamped, ay, acc[1]);
    acc[2] = _mm256_fmadd_ps(clamped, az, acc[2]);
    const __m256 sx = _mm256_mul_ps(live, ax), sy = _mm256_mul_ps(live, ay), sz = _mm256_mul_ps(live, az);
    acc[3] = _mm256_fmadd_ps(sx, ax, acc[3]), acc[4] = _mm256_fmadd_ps(sx, ay, acc[4]);
    acc[5] = _mm256_fmadd_ps(sx, az, acc[5]), acc[6] = _mm256_fmadd_ps(sy, ay, acc[6]);
    acc[7] = _mm256_fmadd_ps(sy, az, acc[7]), acc[8] = _mm256_fmadd_ps(sz, az, acc[8]);
  }
  for (int m = 0; m < 9; ++m) {
    const __m128 h = _mm_add_ps(_mm256_castps256_ps128(acc[m]), _mm256_extractf128_ps(acc[m], 1));
    const __m128 q = _mm_add_ps(h, _mm_movehl_ps(h, h));
    out[m] = _mm_cvtss_f32(_mm_add_ss(q, _mm_shuffle_ps(q, q, 1)));
  }
}

using XyzRows = std::array<std::array<double, K>, 3>;

// fit_zero_clamped's pass: out[0..2] = M·c − Σ_{i in blocks} a_i·min((Φc)_i, 0), the colour of clamp(Φc, 0, ∞)
// when Φc ≥ 0 outside `blocks` (8-knot blocks; the colorimetry rows' pad knot is 0). Two builds as above.
__attribute__((target("avx2,fma"))) void zero_clamped_colour_avx2(const float* columns, const XyzRows& xyz_rows,
                                                                  const float* c, const float* a, uint32_t blocks,
                                                                  double* out) {
  // M·c in double: it is the colour itself, and its terms cancel (coefficients of both signs), so float would
  // cost ~1e-6 of the colour; the clamped knots' part is ~1e-2 of it and stays float.
  __m256d cd[4];
  for (int q = 0; q < 4; ++q) cd[q] = _mm256_cvtps_pd(_mm_loadu_ps(c + 4 * q));
  __m256d unclamped[3];
  for (int m = 0; m < 3; ++m) {
    __m256d s = _mm256_mul_pd(cd[0], _mm256_loadu_pd(xyz_rows[m].data()));
    for (int q = 1; q < 4; ++q) s = _mm256_fmadd_pd(cd[q], _mm256_loadu_pd(xyz_rows[m].data() + 4 * q), s);
    unclamped[m] = s;
  }
  const __m256 zero = _mm256_setzero_ps();
  __m256 acc[3] = {zero, zero, zero};
  for (; blocks != 0; blocks &= blocks - 1) {
    const int b = __builtin_ctz(blocks);
    __m256 even = zero, odd = zero;  // two chains: the 16 multiply-adds of a block are otherwise serial
    for (int k = 0; k < K; k += 2) {
      even = _mm256_fmadd_ps(_mm256_set1_ps(c[k]), _mm256_loadu_ps(columns + k * (n + 1) + 8 * b), even);
      odd = _mm256_fmadd_ps(_mm256_set1_ps(c[k + 1]), _mm256_loadu_ps(columns + (k + 1) * (n + 1) + 8 * b), odd);
    }
    const __m256 negative = _mm256_min_ps(_mm256_add_ps(even, odd), zero);
    for (int m = 0; m < 3; ++m) acc[m] = _mm256_fnmadd_ps(negative, _mm256_loadu_ps(a + m * (n + 1) + 8 * b), acc[m]);
  }
  for (int m = 0; m < 3; ++m) {
    const __m128 h = _mm_add_ps(_mm256_castps256_ps128(acc[m]), _mm256_extractf128_ps(acc[m], 1));
    const __m128 q = _mm_add_ps(h, _mm_movehl_ps(h, h));
    const __m128d d = _mm_add_pd(_mm256_castpd256_pd128(unclamped[m]), _mm256_extractf128_pd(unclamped[m], 1));
    out[m] = _mm_cvtsd_f64(_mm_add_sd(d, _mm_unpackhi_pd(d, d))) + _mm_cvtss_f32(_mm_add_ss(q, _mm_shuffle_ps(q, q, 1)));
  }
}

void zero_clamped_colour_sse(const float* columns, const XyzRows& xyz_rows, const float* c, const float* a,
                             uint32_t blocks, double* out) {
  for (int m = 0; m < 3; ++m) {
    double sum = 0;
    for (int k = 0; k < K; ++k) sum += xyz_rows[m][k] * c[k];
    out[m] = sum;
  }
  for (; blocks != 0; blocks &= blocks - 1) {
    const int b = __builtin_ctz(blocks);
    for (int half = 0; half < 2; ++half) {
      const int first = 8 * b + 4 * half;
      __m128 v = _mm_setzero_ps();
      for (int k = 0; k < K; ++k) v = _mm_add_ps(v, _mm_mul_ps(_mm_set1_ps(c[k]), _mm_loadu_ps(columns + k * (n + 1) + first)));
      const __m128 negative = _mm_min_ps(v, _mm_setzero_ps());
      for (int m = 0; m < 3; ++m) out[m] -= sum(Float4(_mm_mul_ps(negative, _mm_loadu_ps(a + m * (n + 1) + first))));
    }
  }
}

}  // namespace

BasisCoefficients UpsamplingBasis::smooth_coefficients(Chromaticity xy, double angle_rad, double relative_radius,
                                                       SmoothShapeBounds* bounds) const {
  return smooth_coefficients_in_cell(xy, angle_rad * angle_scale_, relative_radius, bounds);
}

BasisCoefficients UpsamplingBasis::smooth_coefficients_in_cell(Chromaticity xy, double angle_cell,
                                                               double relative_radius, SmoothShapeBounds* bounds) const {
  // The same cell and weights as UpsamplingTable::interpolate: periodic uniform angle, rows uniform in
  // u = 1 − √(1 − ρ), weights linear in ρ. Multiplications by precomputed reciprocals, not divisions: this is
  // the setup's critical path.
  double a = angle_cell;
  if (a < 0.0 || a >= angle_count_) a -= std::floor(a * (1.0 / angle_count_)) * angle_count_;
  const int a0 = std::min(int(a), angle_count_ - 1);
  const int a1 = a0 + 1 == angle_count_ ? 0 : a0 + 1;
  const float ta = float(std::clamp(a - a0, 0.0, 1.0));
  const double rho = std::clamp(relative_radius, 0.0, 1.0);
  // The row index only (a float root is exact enough: at a row boundary tr clamps to 0 or 1, continuous either way).
  const float u = (1.0f - std::sqrt(float(1.0 - rho))) * float(radius_count_ - 1);
  const int r0 = std::min(int(u), radius_count_ - 2);
  const float tr = float(std::clamp((rho - radius_rows_[r0]) * row_inverse_spacing_[r0], 0.0, 1.0));
  const size_t e[4] = {size_t(a0) * radius_count_ + r0, size_t(a1) * radius_count_ + r0,
                       size_t(a0) * radius_count_ + r0 + 1, size_t(a1) * radius_count_ + r0 + 1};
  const float w[4] = {(1 - ta) * (1 - tr), ta * (1 - tr), (1 - ta) * tr, ta * tr};
  // Everything blended in one call: the summary first (the solve needs it), then the coefficients and the
  // correction directions, which need only the weights, so their loads and multiply-adds overlap the solve below.
  const float* corner[4] = {entries_[e[0]].parts[0].c.data(), entries_[e[1]].parts[0].c.data(),
                            entries_[e[2]].parts[0].c.data(), entries_[e[3]].parts[0].c.data()};
  // The coefficients, then D's columns X, Y, Z (uninitialised: all written), D straight into the bounds if asked.
  alignas(16) float blended[4][K];
  static_assert(sizeof(bounds->directions) == 3 * sizeof(blended[0]));
  const float* summaries[4] = {entries_[e[0]].summary.data(), entries_[e[1]].summary.data(),
                               entries_[e[2]].summary.data(), entries_[e[3]].summary.data()};
  alignas(16) float summary[16];  // M·c, M·D, the peak and δ are linear in the entries too: interpolated
  if (avx2_fma_) blend_corners_avx2(summaries, corner, w, summary, blended[0], bounds ? bounds->directions : &blended[1]);
  else blend_corners_sse(summaries, corner, w, summary, blended[0], bounds ? bounds->directions : &blended[1]);
  const float(*directions)[K] = bounds ? bounds->directions : &blended[1];
  // Exact colour: c += D·λ with (M·D)·λ = t + δ − M·c, δ the clamping offset. Cramer's rule on the 3×3 (one
  // set of cofactors for the determinant and the solution).
  const double inv_y = 1.0 / xy.y;
  const Xyz colour{xy.x * inv_y, 1.0, (1.0 - xy.x - xy.y) * inv_y};
  const double r[3] = {colour.x + summary[13] - summary[0], 1.0 + summary[14] - summary[1],
                       colour.z + summary[15] - summary[2]};
  const double m00 = summary[3], m01 = summary[4], m02 = summary[5], m10 = summary[6], m11 = summary[7],
               m12 = summary[8], m20 = summary[9], m21 = summary[10], m22 = summary[11];
  const double c00 = m11 * m22 - m12 * m21, c01 = m12 * m20 - m10 * m22, c02 = m10 * m21 - m11 * m20;
  const double det = m00 * c00 + m01 * c01 + m02 * c02;
  const double trace = m00 + m11 + m22;
  float lambda[3] = {0, 0, 0};
  if (std::abs(det) > 1e-12 * trace * trace * trace) {
    const double inv = 1.0 / det;
    lambda[0] = float((c00 * r[0] + (m02 * m21 - m01 * m22) * r[1] + (m01 * m12 - m02 * m11) * r[2]) * inv);
    lambda[1] = float((c01 * r[0] + (m00 * m22 - m02 * m20) * r[1] + (m02 * m10 - m00 * m12) * r[2]) * inv);
    lambda[2] = float((c02 * r[0] + (m01 * m20 - m00 * m21) * r[1] + (m00 * m11 - m01 * m10) * r[2]) * inv);
  }
  BasisCoefficients out;
  const Float4 l0(lambda[0]), l1(lambda[1]), l2(lambda[2]);
  for (int k = 0; k < K; k += 4) {
    const Float4 base(_mm_load_ps(&blended[0][k]));
    const Float4 dx(_mm_load_ps(&directions[0][k])), dy(_mm_load_ps(&directions[1][k])), dz(_mm_load_ps(&directions[2][k]));
    _mm_store_ps(&out.c[k], (base + (l0 * dx + (l1 * dy + l2 * dz))).v);
  }
  if (bounds) {
    // The correction changes knot i by about S_i (Aᵀλ)_i (its projection rings a little more: 2 % slack).
    const double change = std::abs(lambda[0]) * largest_row_[0] + std::abs(lambda[1]) * largest_row_[1] +
                          std::abs(lambda[2]) * largest_row_[2];
    bounds->peak_bound = float(summary[12] * (1.0 + change) * 1.02);
    bounds->colour = colour;
    bounds->rings = std::abs(summary[13]) + std::abs(summary[14]) + std::abs(summary[15]) > 0.0f;
    bounds->low_blocks = change < kMaxLowChange
                             ? uint32_t(low_blocks_[e[0]] | low_blocks_[e[1]] | low_blocks_[e[2]] | low_blocks_[e[3]])
                             : kAllBlocks;
    std::copy(summary + 3, summary + 12, bounds->colour_per_direction.begin());
  }
  return out;
}

std::array<BasisCoefficients, 3> UpsamplingBasis::correction_directions(const SmoothShapeBounds& bounds,
                                                                        float scale) const {
  std::array<BasisCoefficients, 3> out;
  for (int m = 0; m < 3; ++m)
    for (int k = 0; k < K; ++k) out[m].c[k] = bounds.directions[m][k] * scale;
  return out;
}

void UpsamplingBasis::clamped_pass_sse(const BasisCoefficients& c, const float* given, float given_scale,
                                       const float* const a[3], float upper, float* out) const {
  alignas(16) float knots[n + 1];
  if (given) {
    for (int i = 0; i < n + 1; ++i) knots[i] = given[i] * given_scale;
  } else {
    knots_float(c, knots);
  }
  const __m128 lower_v = _mm_setzero_ps(), upper_v = _mm_set1_ps(upper);
  __m128 xyz[3] = {_mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps()};
  __m128 j[6] = {_mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps(),
                 _mm_setzero_ps()};
  for (int i = 0; i < n + 1; i += 4) {
    const __m128 v = _mm_load_ps(knots + i);
    const __m128 clamped = _mm_min_ps(_mm_max_ps(v, lower_v), upper_v);
    const __m128 live = _mm_and_ps(_mm_cmpeq_ps(v, clamped), clamped);  // S_i where live, else 0
    const __m128 ax = _mm_loadu_ps(a[0] + i), ay = _mm_loadu_ps(a[1] + i), az = _mm_loadu_ps(a[2] + i);
    xyz[0] = _mm_add_ps(xyz[0], _mm_mul_ps(clamped, ax));
    xyz[1] = _mm_add_ps(xyz[1], _mm_mul_ps(clamped, ay));
    xyz[2] = _mm_add_ps(xyz[2], _mm_mul_ps(clamped, az));
    const __m128 sx = _mm_mul_ps(live, ax), sy = _mm_mul_ps(live, ay), sz = _mm_mul_ps(live, az);
    j[0] = _mm_add_ps(j[0], _mm_mul_ps(sx, ax)), j[1] = _mm_add_ps(j[1], _mm_mul_ps(sx, ay));
    j[2] = _mm_add_ps(j[2], _mm_mul_ps(sx, az)), j[3] = _mm_add_ps(j[3], _mm_mul_ps(sy, ay));
    j[4] = _mm_add_ps(j[4], _mm_mul_ps(sy, az)), j[5] = _mm_add_ps(j[5], _mm_mul_ps(sz, az));
  }
  for (int m = 0; m < 3; ++m) out[m] = sum(Float4(xyz[m]));
  for (int m = 0; m < 6; ++m) out[3 + m] = sum(Float4(j[m]));
}

template <class Pass>
double UpsamplingBasis::newton_fit(BasisCoefficients& c, const std::array<BasisCoefficients, 3>& directions,
                                   const Xyz& target, const Pass& pass, const Matrix3* fixed_inverse,
                                   int max_steps) const {
  // The best coefficients seen are kept, and a step that overshoots (the live set changed) is halved.
  BasisCoefficients best = c;
  double best_error = INFINITY;
  const double tolerance = kFitTolerance * (std::abs(target.x) + std::abs(target.y) + std::abs(target.z));
  float step_scale = 1.0f, last_lambda[3] = {0, 0, 0};
  auto step_along = [&](BasisCoefficients& x, float scale) {
    for (int k = 0; k < K; k += 4) {
      __m128 s = _mm_load_ps(&x.c[k]);
      for (int m = 0; m < 3; ++m)
        s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(scale * last_lambda[m]), _mm_load_ps(&directions[m].c[k])));
      _mm_store_ps(&x.c[k], s);
    }
  };
  for (int step = 0; step < max_steps; ++step) {
    double sums[9];
    pass(c, step, sums);
    const std::array<double, 3> residual = {target.x - sums[0], target.y - sums[1], target.z - sums[2]};
    const double error = std::abs(residual[0]) + std::abs(residual[1]) + std::abs(residual[2]);
    if (!(error < best_error)) {
      step_scale *= 0.5f;  // overshoot: back to the best point, half the step
      c = best;
      step_along(c, step_scale);
      continue;
    }
    best = c, best_error = error, step_scale = 1.0f;
    if (error <= tolerance) break;
    std::array<double, 3> lambda;
    if (fixed_inverse) {
      lambda = fixed_inverse->apply(residual);
    } else {
      Matrix3 jacobian;
      const double jxx = sums[3], jxy = sums[4], jxz = sums[5], jyy = sums[6], jyz = sums[7], jzz = sums[8];
      jacobian.m = {{{jxx, jxy, jxz}, {jxy, jyy, jyz}, {jxz, jyz, jzz}}};
      const double scale = jxx + jyy + jzz;
      if (!(std::abs(jacobian.determinant()) > 1e-12 * scale * scale * scale)) break;
      lambda = jacobian.inverse().apply(residual);
    }
    for (int m = 0; m < 3; ++m) last_lambda[m] = float(lambda[m]);
    step_along(c, 1.0f);
  }
  c = best;
  return best_error / (std::abs(target.x) + std::abs(target.y) + std::abs(target.z));
}

double UpsamplingBasis::fit_clamped(BasisCoefficients& c, const std::array<BasisCoefficients, 3>& directions,
                                    const Xyz& target, float upper, const float* first_knots,
                                    float first_knots_scale) const {
  // Newton's method on the colour of the clamped spectrum. A step along direction m changes knot i by about
  // S_i a_m,i (D's definition, before projection onto the basis), so the clamped colour's Jacobian is
  // J_rm ≈ Σ_{i live} a_r,i S_i a_m,i, live = the knots inside (0, upper): one 95-knot pass gives the colour and
  // J (A rows have a zero pad, so knot 95 adds nothing).
  const float* a[3] = {&colorimetry_rows_[0], &colorimetry_rows_[n + 1], &colorimetry_rows_[2 * (n + 1)]};
  const auto pass = [&](const BasisCoefficients& x, int step, double* sums) {
    const float* given = step == 0 ? first_knots : nullptr;
    alignas(16) float out[9];
    if (avx2_fma_) clamped_pass_avx2(columns_.data(), x.c.data(), given, first_knots_scale, a[0], upper, out);
    else clamped_pass_sse(x, given, first_knots_scale, a, upper, out);
    std::copy(out, out + 9, sums);
  };
  return newton_fit(c, directions, target, pass, nullptr, 8);
}

double UpsamplingBasis::fit_zero_clamped(BasisCoefficients& c, const SmoothShapeBounds& bounds, float scale,
                                         const Xyz& target, float upper) const {
  // The Jacobian: a step λ along the scaled directions changes M·c by scale·(M·D)·λ, and the knots it would
  // clamp have S_i ≈ 0 (D moves knot i by about S_i a_i), so clamping barely changes it: fixed for the fit.
  Matrix3 jacobian;
  for (int r = 0; r < 3; ++r)
    for (int m = 0; m < 3; ++m) jacobian.m[r][m] = double(scale) * bounds.colour_per_direction[size_t(3 * r + m)];
  const double size = std::abs(jacobian(0, 0)) + std::abs(jacobian(1, 1)) + std::abs(jacobian(2, 2));
  if (!(std::abs(jacobian.determinant()) > 1e-12 * size * size * size))
    return fit_clamped(c, correction_directions(bounds, scale), target, upper);
  const Matrix3 inverse = jacobian.inverse();
  const float* a = colorimetry_rows_.data();
  const auto pass = [&](const BasisCoefficients& x, int, double* sums) {
    if (avx2_fma_) zero_clamped_colour_avx2(columns_.data(), xyz_rows_, x.c.data(), a, bounds.low_blocks, sums);
    else zero_clamped_colour_sse(columns_.data(), xyz_rows_, x.c.data(), a, bounds.low_blocks, sums);
  };
  const std::array<BasisCoefficients, 3> directions = correction_directions(bounds, scale);
  const double left = newton_fit(c, directions, target, pass, &inverse, kZeroOnlySteps);
  // The verification: the block pass's colour is the clamped spectrum's only if no knot outside the low blocks is
  // negative and none exceeds `upper`. Where that fails, or the fixed Jacobian converged too slowly (many clamped
  // knots, near the locus), the full fit takes over from the best point reached, its first pass these knots.
  alignas(16) float knots[n + 1];
  uint32_t negative = 0;
  const float peak = knots_float(c, knots, &negative);
  const bool valid = peak <= upper && left <= kFitTolerance && (negative & ~bounds.low_blocks) == 0;
  return valid ? left : fit_clamped(c, directions, target, upper, knots, 1.0f);
}

uint32_t UpsamplingBasis::negative_blocks(const BasisCoefficients& c) const {
  alignas(16) float v[n + 1];
  uint32_t negative = 0;
  knots_float(c, v, &negative);
  return negative;
}

void UpsamplingBasis::fill(BasisAtWavelengths& cache, Float4 lambda_nm) const {
  const Float4 x = clamp((lambda_nm - Float4(float(kUpsampleFirstKnotNm))) * Float4(float(1.0 / kUpsampleKnotSpacingNm)),
                         Float4(0.0f), Float4(float(n - 1)));
  const Float4 base = floor(x);
  const Float4 t = x - base;
  for (int lane = 0; lane < 4; ++lane) {
    // Knot 94 is the last; its row is repeated as the pad row 95, so a lane at 830 nm reads rows 94 and 95.
    const float* row = &rows_[size_t(base[lane]) * K];
    const __m128 weight = _mm_set1_ps(t[lane]);
    for (int k = 0; k < K; k += 4) {
      const __m128 lo = _mm_loadu_ps(row + k), hi = _mm_loadu_ps(row + K + k);
      _mm_store_ps(&cache.phi[lane][k], _mm_add_ps(lo, _mm_mul_ps(weight, _mm_sub_ps(hi, lo))));
    }
  }
  _mm_store_ps(cache.lambda_nm, lambda_nm.v);
  cache.basis_id = id_;
}

KnotValues UpsamplingBasis::knots(const BasisCoefficients& c) const {
  KnotValues out{};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < K; ++k) out[i] += double(rows_[size_t(i) * K + k]) * c.c[k];
  return out;
}

// The setup's one heavy loop (96 × 16 multiply-adds), in two builds chosen once per basis by the CPU: AVX2 + FMA
// (twelve 8-lane accumulators) and the SSE4.1 baseline (written plainly for the compiler to vectorise).
// Both also report the 8-knot blocks holding a negative knot (bit b: knots 8b .. 8b + 7; the pad repeats knot 94).
__attribute__((target("avx2,fma"))) static float knot_values_avx2(const float* columns, const float* c, float* out,
                                                                  uint32_t* negative) {
  constexpr int kBlocks = (n + 1) / 8;
  __m256 v[kBlocks];
  for (int b = 0; b < kBlocks; ++b) v[b] = _mm256_setzero_ps();
  for (int k = 0; k < K; ++k) {
    const __m256 ck = _mm256_set1_ps(c[k]);
    for (int b = 0; b < kBlocks; ++b) v[b] = _mm256_fmadd_ps(ck, _mm256_loadu_ps(columns + k * (n + 1) + 8 * b), v[b]);
  }
  __m256 peak = v[0];
  uint32_t below = 0;
  for (int b = 0; b < kBlocks; ++b) {
    _mm256_storeu_ps(out + 8 * b, v[b]);
    peak = _mm256_max_ps(peak, v[b]);  // the pad (knot 95) repeats knot 94, so it cannot raise the maximum
    below |= uint32_t(_mm256_movemask_ps(_mm256_cmp_ps(v[b], _mm256_setzero_ps(), _CMP_LT_OQ)) != 0) << b;
  }
  *negative = below;
  __m128 h = _mm_max_ps(_mm256_castps256_ps128(peak), _mm256_extractf128_ps(peak, 1));
  h = _mm_max_ps(h, _mm_movehl_ps(h, h));
  return _mm_cvtss_f32(_mm_max_ss(h, _mm_shuffle_ps(h, h, 1)));
}

static float knot_values(const float* columns, const float* c, float* out, uint32_t* negative) {
  float values[n + 1] = {};
  for (int k = 0; k < K; ++k)
    for (int i = 0; i < n + 1; ++i) values[i] += c[k] * columns[k * (n + 1) + i];
  float peak = values[0];
  uint32_t below = 0;
  for (int i = 0; i < n + 1; ++i) {
    out[i] = values[i];
    peak = std::max(peak, values[i]);
    below |= uint32_t(values[i] < 0.0f) << (i / 8);
  }
  *negative = below;
  return peak;
}

float UpsamplingBasis::knots_float(const BasisCoefficients& c, float* out, uint32_t* negative_blocks) const {
  uint32_t negative = 0;
  const float peak = avx2_fma_ ? knot_values_avx2(columns_.data(), c.c.data(), out, &negative)
                               : knot_values(columns_.data(), c.c.data(), out, &negative);
  if (negative_blocks) *negative_blocks = negative;
  return peak;
}

Xyz UpsamplingBasis::xyz_of(const BasisCoefficients& c) const {
  Xyz out;
  for (int k = 0; k < K; ++k) {
    out.x += xyz_rows_[0][k] * c.c[k];
    out.y += xyz_rows_[1][k] * c.c[k];
    out.z += xyz_rows_[2][k] * c.c[k];
  }
  return out;
}

}  // namespace rimu
