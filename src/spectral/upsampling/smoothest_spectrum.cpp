#include "spectral/upsampling/smoothest_spectrum.h"

#include <cmath>
#include <utility>
#include <vector>

#include "spectral/upsampling/dense_linear_solve.h"

namespace rimu {
namespace {

constexpr int kKnots = kUpsampleKnotCount;

/// (L·S)_i for L = DᵀD, D the first-difference operator: the tridiagonal (−1, 2, −1) with 1 at both ends.
double laplacian_row(const KnotValues& s, int i) {
  double v = 0;
  if (i > 0) v += s[i] - s[i - 1];
  if (i < kKnots - 1) v += s[i] - s[i + 1];
  return v;
}

}  // namespace

double roughness(const KnotValues& knots) {
  double sum = 0;
  for (int i = 0; i + 1 < kKnots; ++i) sum += (knots[i + 1] - knots[i]) * (knots[i + 1] - knots[i]);
  return sum;
}

std::optional<SmoothestSpectrum> smoothest_knot_spectrum(const KnotColorimetry& colorimetry, const Xyz& target) {
  // Lagrangian SᵀLS + μᵀ(AS − t) − νᵀS. On the free knots F (bounds inactive) stationarity and feasibility give
  // the KKT system [2L_FF  A_Fᵀ; A_F  0] [S_F; μ] = [0; t]; on the bound knots S = 0 and ν = (2LS + Aᵀμ) ≥ 0.
  // Each step solves that system; knots that went negative are bound, then a bound knot whose ν is negative
  // (it wants to rise) is freed. Freeing one at a time and binding all violators is the usual working-set rule.
  const double t[3] = {target.x, target.y, target.z};
  std::array<bool, kKnots> bound{};
  SmoothestSpectrum result;
  for (int iteration = 1; iteration <= 400; ++iteration) {
    std::vector<int> free;
    for (int i = 0; i < kKnots; ++i)
      if (!bound[i]) free.push_back(i);
    const int f = int(free.size());
    if (f < 1) return std::nullopt;
    const int size = f + 3;
    std::vector<double> m(size * size, 0.0), rhs(size, 0.0);
    for (int a = 0; a < f; ++a) {
      const int i = free[a];
      for (int b = 0; b < f; ++b) {
        const int j = free[b];
        double l = 0;
        if (i == j) l = (i > 0) + (i < kKnots - 1);
        else if (std::abs(i - j) == 1) l = -1;
        m[a * size + b] = 2 * l;
      }
      for (int k = 0; k < 3; ++k) {
        m[a * size + f + k] = colorimetry.row(k)[i];
        m[(f + k) * size + a] = colorimetry.row(k)[i];
      }
    }
    for (int k = 0; k < 3; ++k) rhs[f + k] = t[k];
    if (!solve_dense(m, rhs, size)) return std::nullopt;  // fewer than 3 independent free knots: outside the hull
    KnotValues s{};
    for (int a = 0; a < f; ++a) s[free[a]] = rhs[a];
    const double mu[3] = {rhs[f], rhs[f + 1], rhs[f + 2]};
    result.knots = s;
    result.iterations = iteration;

    double scale = 0;
    for (double v : s) scale = std::fmax(scale, std::abs(v));
    const double tolerance = 1e-12 * scale;
    bool changed = false;
    for (int i = 0; i < kKnots; ++i)
      if (!bound[i] && s[i] < -tolerance) bound[i] = changed = true;
    if (changed) continue;

    int most_negative = -1;
    double worst = -1e-10 * scale;
    for (int i = 0; i < kKnots; ++i) {
      if (!bound[i]) continue;
      const double nu = 2 * laplacian_row(s, i) + mu[0] * colorimetry.row(0)[i] + mu[1] * colorimetry.row(1)[i] +
                        mu[2] * colorimetry.row(2)[i];
      if (nu < worst) worst = nu, most_negative = i;
    }
    if (most_negative < 0) {
      for (double& v : result.knots) v = std::fmax(v, 0.0);
      // A singular-but-solved system can still miss the target: accept only a true solution.
      const Xyz got = colorimetry.xyz_of(result.knots);
      const double error = std::abs(got.x - target.x) + std::abs(got.y - target.y) + std::abs(got.z - target.z);
      if (!(error <= 1e-9 * (std::abs(target.x) + std::abs(target.y) + std::abs(target.z)))) return std::nullopt;
      return result;
    }
    bound[most_negative] = false;
  }
  return std::nullopt;
}

}  // namespace rimu
