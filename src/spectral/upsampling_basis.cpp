#include "spectral/upsampling_basis.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <numbers>

#include "spectral/matrix3.h"

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

UpsamplingBasis::UpsamplingBasis(const UpsamplingTable& table, const KnotColorimetry& colorimetry)
    : angle_count_(table.angle_count), radius_count_(table.radius_count) {
  static std::atomic<uint64_t> next_id{1};
  id_ = next_id.fetch_add(1);
  for (int r = 0; r < radius_count_; ++r) radius_rows_.push_back(table.radius_of_row(r));
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
  entry_.resize(entries);
  for (size_t e = 0; e < entries; ++e) {
    Vector s = shapes[e];
    for (double& v : s) v /= table.luminance_limits[e];  // Y = 1
    Vector weighted[3];  // diag(S) a_m
    for (int m = 0; m < 3; ++m)
      for (int i = 0; i < n; ++i) weighted[m][i] = s[i] * a[m][i];
    for (int k = 0; k < K; ++k) {
      entry_[e][0].c[k] = float(dot(s, basis[k]));
      for (int m = 0; m < 3; ++m) entry_[e][m + 1].c[k] = float(dot(basis[k], weighted[m]));  // D = Φᵀ diag(S) Aᵀ
    }
  }
  // Clamping at zero moves the colour of spectra that ring around a zero region. At each entry the coefficients
  // are fitted so that the clamped spectrum has the entry's colour, and the offset δ = M·c − colour(clamped) is
  // kept: interpolated, it lets smooth_coefficients aim the unclamped colour at t + δ, so that the clamped one
  // lands on t without a 95-knot pass (docs/upsampling.md "Fast path").
  colorimetry_rows_.assign(3 * size_t(n + 1), 0.0f);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < n; ++i) colorimetry_rows_[size_t(c) * (n + 1) + i] = float(a[c][i]);
  summary_.resize(entries);
  for (size_t e = 0; e < entries; ++e) {
    const Xyz target = xyz_of(entry_[e][0]);
    fit_clamped(entry_[e][0], {entry_[e][1], entry_[e][2], entry_[e][3]}, target, INFINITY);
    const Xyz fitted = xyz_of(entry_[e][0]);
    summary_[e].v[13] = float(fitted.x - target.x), summary_[e].v[14] = float(fitted.y - target.y),
    summary_[e].v[15] = float(fitted.z - target.z);
  }
  for (size_t e = 0; e < entries; ++e) {
    std::array<float, 16>& v = summary_[e].v;
    for (int part = 0; part < 4; ++part) {
      const Xyz x = xyz_of(entry_[e][part]);
      if (part == 0) v[0] = float(x.x), v[1] = float(x.y), v[2] = float(x.z);
      else v[3 + 0 * 3 + (part - 1)] = float(x.x), v[3 + 1 * 3 + (part - 1)] = float(x.y), v[3 + 2 * 3 + (part - 1)] = float(x.z);
    }
    const KnotValues knots_e = knots(entry_[e][0]);
    v[12] = float(*std::max_element(knots_e.begin(), knots_e.end()));
  }
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i < n; ++i) largest_row_[m] = std::max(largest_row_[m], std::abs(a[m][i]));

  const KnotGamut gamut = table.gamut();
  usable_radius_.resize(kRadiusSteps + 1);
  for (int s = 0; s <= kRadiusSteps; ++s)
    usable_radius_[s] =
        float(gamut.boundary_radius(-std::numbers::pi + 2 * std::numbers::pi * s / kRadiusSteps) * table.usable_fraction);
}

double UpsamplingBasis::usable_radius(double angle_rad) const {
  const double x = std::clamp((angle_rad + std::numbers::pi) / (2 * std::numbers::pi) * kRadiusSteps, 0.0,
                              double(kRadiusSteps));
  const int i = std::min(int(x), kRadiusSteps - 1);
  const double t = x - i;
  return usable_radius_[i] + t * (usable_radius_[i + 1] - usable_radius_[i]);
}

BasisCoefficients UpsamplingBasis::smooth_coefficients(Chromaticity xy, double angle_rad, double relative_radius,
                                                       SmoothShapeBounds* bounds) const {
  // The same cell and weights as UpsamplingTable::interpolate: periodic uniform angle, rows uniform in
  // u = 1 − √(1 − ρ), weights linear in ρ.
  double a = angle_rad / (2 * std::numbers::pi) * angle_count_;
  a -= std::floor(a / angle_count_) * angle_count_;
  const int a0 = std::min(int(a), angle_count_ - 1);
  const int a1 = (a0 + 1) % angle_count_;
  const float ta = float(std::clamp(a - a0, 0.0, 1.0));
  const double rho = std::clamp(relative_radius, 0.0, 1.0);
  const double u = (1.0 - std::sqrt(1.0 - rho)) * (radius_count_ - 1);
  const int r0 = std::min(int(u), radius_count_ - 2);
  const float tr =
      float(std::clamp((rho - radius_rows_[r0]) / (radius_rows_[r0 + 1] - radius_rows_[r0]), 0.0, 1.0));
  const std::array<BasisCoefficients, 4>* corner[4] = {
      &entry_[size_t(a0) * radius_count_ + r0], &entry_[size_t(a1) * radius_count_ + r0],
      &entry_[size_t(a0) * radius_count_ + r0 + 1], &entry_[size_t(a1) * radius_count_ + r0 + 1]};
  const __m128 w[4] = {_mm_set1_ps((1 - ta) * (1 - tr)), _mm_set1_ps(ta * (1 - tr)), _mm_set1_ps((1 - ta) * tr),
                       _mm_set1_ps(ta * tr)};
  BasisCoefficients blend[4];  // the coefficients and the three correction directions
  for (int part = 0; part < 4; ++part)
    for (int k = 0; k < K; k += 4) {
      __m128 s = _mm_mul_ps(w[0], _mm_load_ps(&(*corner[0])[part].c[k]));
      for (int c = 1; c < 4; ++c) s = _mm_add_ps(s, _mm_mul_ps(w[c], _mm_load_ps(&(*corner[c])[part].c[k])));
      _mm_store_ps(&blend[part].c[k], s);
    }
  // M·c and M·D are linear in the entries too: interpolated, not recomputed.
  const EntrySummary* sum_corner[4] = {&summary_[size_t(a0) * radius_count_ + r0], &summary_[size_t(a1) * radius_count_ + r0],
                                       &summary_[size_t(a0) * radius_count_ + r0 + 1],
                                       &summary_[size_t(a1) * radius_count_ + r0 + 1]};
  alignas(16) float summary[16];
  for (int j = 0; j < 16; j += 4) {
    __m128 s = _mm_mul_ps(w[0], _mm_load_ps(&sum_corner[0]->v[j]));
    for (int c = 1; c < 4; ++c) s = _mm_add_ps(s, _mm_mul_ps(w[c], _mm_load_ps(&sum_corner[c]->v[j])));
    _mm_store_ps(summary + j, s);
  }
  // Exact colour: c += D·λ with (M·D)·λ = t + δ − M·c, δ the clamping offset.
  const std::array<double, 3> residual = {xy.x / xy.y + summary[13] - summary[0], 1.0 + summary[14] - summary[1],
                                          (1.0 - xy.x - xy.y) / xy.y + summary[15] - summary[2]};
  Matrix3 md;
  for (int row = 0; row < 3; ++row)
    for (int m = 0; m < 3; ++m) md(row, m) = summary[3 + row * 3 + m];
  std::array<double, 3> lambda{};
  const double scale = md(0, 0) + md(1, 1) + md(2, 2);
  if (std::abs(md.determinant()) > 1e-12 * scale * scale * scale) lambda = md.inverse().apply(residual);
  BasisCoefficients out = blend[0];
  for (int k = 0; k < K; k += 4) {
    __m128 s = _mm_load_ps(&out.c[k]);
    for (int m = 0; m < 3; ++m) s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(float(lambda[m])), _mm_load_ps(&blend[m + 1].c[k])));
    _mm_store_ps(&out.c[k], s);
  }
  if (bounds) {
    bounds->directions = {blend[1], blend[2], blend[3]};
    // The correction changes knot i by about S_i (Aᵀλ)_i (its projection rings a little more: 2 % slack).
    const double change = std::abs(lambda[0]) * largest_row_[0] + std::abs(lambda[1]) * largest_row_[1] +
                          std::abs(lambda[2]) * largest_row_[2];
    bounds->peak_bound = float(summary[12] * (1.0 + change) * 1.02);
    bounds->clamp_offset = {summary[13], summary[14], summary[15]};
    bounds->rings = std::abs(summary[13]) + std::abs(summary[14]) + std::abs(summary[15]) > 0.0f;
  }
  return out;
}

double UpsamplingBasis::fit_clamped(BasisCoefficients& c, const std::array<BasisCoefficients, 3>& directions,
                                    const Xyz& target, float upper, const float* first_knots,
                                    float first_knots_scale) const {
  // Newton's method on the colour of the clamped spectrum. A step along direction m changes knot i by about
  // S_i a_m,i (D's definition, before projection onto the basis), so the clamped colour's Jacobian is
  // J_rm ≈ Σ_{i live} a_r,i S_i a_m,i, live = the knots inside (0, upper): one 95-knot pass gives the colour and
  // J. The best coefficients seen are kept, and a step that overshoots (the live set changed) is halved.
  const __m128 lower_v = _mm_setzero_ps(), upper_v = _mm_set1_ps(upper);
  const float* a[3] = {&colorimetry_rows_[0], &colorimetry_rows_[n + 1], &colorimetry_rows_[2 * (n + 1)]};
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
  for (int step = 0; step < 8; ++step) {
    alignas(16) float knots[n + 1];
    if (step == 0 && first_knots) {
      for (int i = 0; i < n + 1; ++i) knots[i] = first_knots[i] * first_knots_scale;
    } else {
      knots_float(c, knots);
    }
    // XYZ of the clamped spectrum (A rows have a zero pad, so knot 95 adds nothing) and the six sums of J.
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
    const std::array<double, 3> residual = {target.x - sum(Float4(xyz[0])), target.y - sum(Float4(xyz[1])),
                                            target.z - sum(Float4(xyz[2]))};
    const double error = std::abs(residual[0]) + std::abs(residual[1]) + std::abs(residual[2]);
    if (!(error < best_error)) {
      step_scale *= 0.5f;  // overshoot: back to the best point, half the step
      c = best;
      step_along(c, step_scale);
      continue;
    }
    best = c, best_error = error, step_scale = 1.0f;
    if (error <= tolerance) break;
    Matrix3 jacobian;
    const double jxx = sum(Float4(j[0])), jxy = sum(Float4(j[1])), jxz = sum(Float4(j[2])), jyy = sum(Float4(j[3])),
                 jyz = sum(Float4(j[4])), jzz = sum(Float4(j[5]));
    jacobian.m = {{{jxx, jxy, jxz}, {jxy, jyy, jyz}, {jxz, jyz, jzz}}};
    const double scale = jxx + jyy + jzz;
    if (!(std::abs(jacobian.determinant()) > 1e-12 * scale * scale * scale)) break;
    const auto lambda = jacobian.inverse().apply(residual);
    for (int m = 0; m < 3; ++m) last_lambda[m] = float(lambda[m]);
    step_along(c, 1.0f);
  }
  c = best;
  return best_error / (std::abs(target.x) + std::abs(target.y) + std::abs(target.z));
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

// The setup's one heavy loop (95 × 16 multiply-adds): written plainly so the compiler vectorises it, and built
// twice, for AVX2+FMA (8 lanes, fused: ~3× faster) and for the baseline SSE4.1, chosen at load by the CPU.
__attribute__((target_clones("avx2,fma", "default"))) static float knot_values(const float* columns, const float* c,
                                                                               float* out) {
  float values[n + 1] = {};
  for (int k = 0; k < K; ++k)
    for (int i = 0; i < n + 1; ++i) values[i] += c[k] * columns[k * (n + 1) + i];
  float peak = values[0];
  for (int i = 0; i < n + 1; ++i) {
    out[i] = values[i];
    peak = std::max(peak, values[i]);  // the pad (column 95) repeats knot 94, so it cannot raise the maximum
  }
  return peak;
}

float UpsamplingBasis::knots_float(const BasisCoefficients& c, float* out) const {
  return knot_values(columns_.data(), c.c.data(), out);
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
