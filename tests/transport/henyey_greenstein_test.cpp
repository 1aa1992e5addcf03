// The Henyey–Greenstein phase function: normalisation, mean cosine, and sampling against the density (chi-square).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "statistics.h"
#include "transport/geometry/frame.h"
#include "transport/media/henyey_greenstein.h"

namespace rimu {
namespace {

// Simpson's rule over μ ∈ [a, b] of 2π·p(μ)·h(μ) (the azimuth integrates to 2π).
template <typename H>
double integrate_mu(float g, double a, double b, H&& h, int n = 2000) {
  const double step = (b - a) / n;
  double s = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double mu = a + i * step;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    s += w * 2.0 * std::numbers::pi * henyey_greenstein(float(mu), g) * h(mu);
  }
  return s * step / 3.0;
}

}  // namespace

TEST_CASE("Henyey-Greenstein is normalised and its mean cosine is g") {
  // Henyey & Greenstein 1941: ∫p dω = 1 and ⟨cos θ⟩ = g by construction. Simpson with 2000 intervals on a smooth
  // integrand (g ≤ 0.9: the peak 1/(1−g)³ is resolved) is accurate to < 1e-4; float evaluation adds ~1e-6.
  for (float g : {-0.7f, -0.3f, 0.0f, 0.0005f, 0.3f, 0.7f, 0.9f}) {
    CAPTURE(g);
    CHECK(integrate_mu(g, -1.0, 1.0, [](double) { return 1.0; }) == doctest::Approx(1.0).epsilon(2e-4));
    // |g| < 1e-3 is evaluated as isotropic (henyey_greenstein.cpp): its mean cosine is then 0, not g.
    const double expected_mean = std::fabs(g) < 1e-3f ? 0.0 : g;
    CHECK(integrate_mu(g, -1.0, 1.0, [](double mu) { return mu; }) == doctest::Approx(expected_mean).epsilon(2e-4));
  }
}

TEST_CASE("Henyey-Greenstein sampling follows its density, chi-square over cos theta and phi") {
  // Pearson's chi-square over 40 bins in cos θ (θ from the propagation direction −wo) × 8 in φ; expected counts
  // from Simpson integration of the density (independent of the inverse CDF used to sample). Šidák-corrected
  // significance 1% over the 6 values of g: a correct sampler fails with probability 1%.
  const double threshold = test::sidak_threshold(0.01, 6);
  const Vec3 wo = normalize(Vec3{0.3f, -0.5f, 0.8f});
  const Frame frame = Frame::from_normal(-wo);
  constexpr int kMu = 40, kPhi = 8, kSamples = 200000;
  for (float g : {-0.8f, -0.2f, 0.0f, 0.3f, 0.7f, 0.95f}) {
    CAPTURE(g);
    const HenyeyGreenstein hg(g);
    std::vector<double> observed(kMu * kPhi, 0.0);
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    int bad = 0;
    for (int i = 0; i < kSamples; ++i) {
      const PhaseSample s = hg.sample(wo, {uniform(rng), uniform(rng)});
      // The density reported must be the density evaluated for the same direction (MIS relies on it).
      if (std::fabs(s.pdf_solid_angle - hg.eval(wo, s.wi)) > 1e-3f * s.pdf_solid_angle) ++bad;
      const Vec3 local = frame.to_local(s.wi);
      const int bin_mu = std::clamp(int((local.z + 1.0f) * 0.5f * kMu), 0, kMu - 1);
      double phi = std::atan2(local.y, local.x);
      if (phi < 0) phi += 2.0 * std::numbers::pi;
      const int bin_phi = std::clamp(int(phi / (2.0 * std::numbers::pi) * kPhi), 0, kPhi - 1);
      observed[size_t(bin_mu * kPhi + bin_phi)] += 1.0;
    }
    CHECK(bad == 0);
    double chi2 = 0.0;
    int cells = 0;
    double pooled_observed = 0.0, pooled_expected = 0.0;
    for (int m = 0; m < kMu; ++m) {
      const double a = -1.0 + 2.0 * m / kMu, b = a + 2.0 / kMu;
      const double expected = kSamples * integrate_mu(g, a, b, [](double) { return 1.0; }, 200) / kPhi;
      for (int p = 0; p < kPhi; ++p) {
        const double o = observed[size_t(m * kPhi + p)];
        if (expected < 5.0) {  // pool sparse cells (validity of Pearson's test)
          pooled_observed += o;
          pooled_expected += expected;
          continue;
        }
        chi2 += (o - expected) * (o - expected) / expected;
        ++cells;
      }
    }
    if (pooled_expected >= 5.0) {
      chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
      ++cells;
    }
    const double p_value = test::chi_square_p_value(chi2, cells - 1);
    CAPTURE(chi2);
    CAPTURE(cells);
    CHECK(p_value > threshold);
  }
}

}  // namespace rimu
