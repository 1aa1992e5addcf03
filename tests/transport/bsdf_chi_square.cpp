#include "bsdf_chi_square.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "statistics.h"
#include "test_support.h"

namespace rimu::test {
namespace {

constexpr int kCosBins = 20, kPhiBins = 20, kPieces = 2;
using rimu::test::kPi;

int cell_of(Vec3 wi) {
  const int c = std::clamp(int((wi.z + 1.0f) * 0.5f * kCosBins), 0, kCosBins - 1);
  double phi = std::atan2(double(wi.y), double(wi.x));
  if (phi < 0) phi += 2 * kPi;
  const int p = std::clamp(int(phi / (2 * kPi) * kPhiBins), 0, kPhiBins - 1);
  return c * kPhiBins + p;
}

/// ∫ g over [a, b] by adaptive Simpson quadrature (Lyness 1969): a panel is split until its two halves agree
/// with the whole to `tolerance` (Richardson's 15), so narrow lobes get many points and flat regions few.
template <typename G>
double adaptive_simpson(const G& g, double a, double b, double fa, double fm, double fb, double whole,
                        double tolerance, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = g(lm), frm = g(rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  const double delta = left + right - whole;
  if (depth <= 0 || std::fabs(delta) <= 15 * tolerance) return left + right + delta / 15;
  return adaptive_simpson(g, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
         adaptive_simpson(g, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

/// ∫ g over [a, b], started on `pieces` panels so that a lobe narrower than the interval is not stepped over.
template <typename G>
double integrate(const G& g, double a, double b, int pieces, double tolerance) {
  double total = 0;
  const double h = (b - a) / pieces;
  for (int i = 0; i < pieces; ++i) {
    const double x0 = a + i * h, x1 = x0 + h, xm = 0.5 * (x0 + x1);
    const double f0 = g(x0), fm = g(xm), f1 = g(x1);
    total += adaptive_simpson(g, x0, x1, f0, fm, f1, h / 6 * (f0 + 4 * fm + f1), tolerance / pieces, 12);
  }
  return total;
}

/// ∫ pdf over one (cos θ, φ) cell, nested adaptive quadrature in θ (with the sin θ Jacobian) and φ.
/// The tolerance, 1e-6 of probability per cell, is 0.1 of a count at 10⁵ samples: negligible against the
/// Poisson noise the test measures.
double integrate_cell(const Bsdf& bsdf, Vec3 wo, int cos_bin, int phi_bin) {
  const double c0 = -1.0 + 2.0 * cos_bin / kCosBins, c1 = -1.0 + 2.0 * (cos_bin + 1) / kCosBins;
  const double theta0 = std::acos(std::clamp(c1, -1.0, 1.0)), theta1 = std::acos(std::clamp(c0, -1.0, 1.0));
  const double phi0 = 2 * kPi * phi_bin / kPhiBins, phi1 = 2 * kPi * (phi_bin + 1) / kPhiBins;
  constexpr double kTolerance = 1e-6;
  const auto over_phi = [&](double theta) {
    const double sin_t = std::sin(theta), cos_t = std::cos(theta);
    const auto pdf_at = [&](double phi) {
      const Vec3 wi{float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t)};
      return double(bsdf.pdf(wo, wi)[0]) * sin_t;
    };
    return integrate(pdf_at, phi0, phi1, kPieces, kTolerance / (theta1 - theta0));
  };
  return integrate(over_phi, theta0, theta1, kPieces, kTolerance);
}

}  // namespace

ChiSquareOutcome bsdf_chi_square(const Bsdf& bsdf, Vec3 wo, int sample_count, uint64_t seed) {
  ChiSquareOutcome out;
  constexpr int kDirectional = kCosBins * kPhiBins;
  // Cells [0, kDirectional) are directions; the last two are the delta samples on wo's side and the other side.
  std::vector<double> observed(kDirectional + 2, 0.0), expected(kDirectional + 2, 0.0);
  float delta_probability[2] = {-1.0f, -1.0f};

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int n = 0; n < sample_count; ++n) {
    const float u_lobe = uniform(rng);
    const Vec2 u{uniform(rng), uniform(rng)};
    const auto s = bsdf.sample(wo, u_lobe, u);
    if (!s) continue;
    if (!is_finite(s->wi) || !is_finite(s->f).all() || !is_finite(s->pdf).all() || !(s->pdf[0] > 0.0f)) {
      out.failure = "sample() returned a non-finite value or a zero hero pdf";
      return out;
    }
    if (s->is_delta) {
      const int side = s->wi.z * wo.z > 0.0f ? 0 : 1;
      if (delta_probability[side] < 0.0f) delta_probability[side] = s->pdf[0];
      if (std::fabs(delta_probability[side] - s->pdf[0]) > 1e-6f) {
        out.failure = "delta samples on one side report different probabilities";
        return out;
      }
      observed[kDirectional + side] += 1;
    } else {
      observed[cell_of(s->wi)] += 1;
    }
  }
  for (int c = 0; c < kCosBins; ++c)
    for (int p = 0; p < kPhiBins; ++p) expected[c * kPhiBins + p] = sample_count * integrate_cell(bsdf, wo, c, p);
  for (int side = 0; side < 2; ++side)
    expected[kDirectional + side] = sample_count * std::max(0.0f, delta_probability[side]);

  std::vector<int> order(observed.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
  double pooled_observed = 0, pooled_expected = 0;
  int cells = 0;
  for (int i : order) {
    if (expected[i] == 0.0) {
      // The pdf says nothing can land here; a few hits may come from cells whose mass the quadrature misses.
      if (observed[i] > sample_count * 1e-5) {
        out.failure = "samples in a cell where pdf() integrates to 0 (cell " + std::to_string(i) + ", " +
                      std::to_string(int(observed[i])) + " samples)";
        return out;
      }
      continue;
    }
    pooled_observed += observed[i];
    pooled_expected += expected[i];
    if (pooled_expected < kPearsonMinExpected) continue;
    const double diff = pooled_observed - pooled_expected;
    out.chi_square += diff * diff / pooled_expected;
    ++cells;
    pooled_observed = pooled_expected = 0;
  }
  if (pooled_expected > 0) {  // the remainder, too small to stand alone, still counts
    const double diff = pooled_observed - pooled_expected;
    out.chi_square += diff * diff / pooled_expected;
    ++cells;
  }
  out.degrees_of_freedom = std::max(1, cells - 1);
  out.p_value = chi_square_p_value(out.chi_square, out.degrees_of_freedom);
  return out;
}

}  // namespace rimu::test
