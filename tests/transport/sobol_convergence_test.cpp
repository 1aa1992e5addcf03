// Convergence rates on analytic integrands over [0,1)²: the RMS error of Owen-scrambled Sobol' points falls
// faster than N^-1/2, while independent sampling's falls as N^-1/2. The slope is fitted over N = 2⁴..2¹² from
// many independent randomisations, with its standard error, and the assertions are stated in those units.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "transport/sampling/sampler.h"
#include "test_support.h"

using namespace rimu;

namespace {

constexpr double kE = 2.718281828459045;
using rimu::test::kPi;

// Smooth and non-separable: ∫₀¹∫₀¹ u·e^{uv} dv du = ∫₀¹ (e^u − 1) du = e − 2.
double smooth(double u, double v) { return u * std::exp(u * v); }
constexpr double kSmoothIntegral = kE - 2.0;
// Discontinuous along a curve not aligned with the axes: the quarter disc u² + v² < r², area π r²/4.
constexpr double kRadius = 0.75;
double disc(double u, double v) { return u * u + v * v < kRadius * kRadius ? 1.0 : 0.0; }
constexpr double kDiscIntegral = kPi * kRadius * kRadius / 4.0;

struct Slope {
  double slope = 0, standard_error = 0;
};

// Weighted least-squares fit of log RMSE against log N. Each log RMSE carries the standard error of the mean of
// M squared errors, by the delta method: se(log RMSE) = ½·sd(e²)/(√M·mean(e²)). Levels use disjoint seeds, so
// the points are independent and the fit's standard error is σ_b = (Σ w (x − x̄_w)²)^-½ with w = 1/se².
Slope fit(const std::vector<double>& log_n, const std::vector<double>& log_rmse, const std::vector<double>& se) {
  double sw = 0, swx = 0, swy = 0;
  for (size_t i = 0; i < log_n.size(); ++i) {
    const double w = 1.0 / (se[i] * se[i]);
    sw += w, swx += w * log_n[i], swy += w * log_rmse[i];
  }
  const double mx = swx / sw, my = swy / sw;
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < log_n.size(); ++i) {
    const double w = 1.0 / (se[i] * se[i]);
    sxx += w * (log_n[i] - mx) * (log_n[i] - mx);
    sxy += w * (log_n[i] - mx) * (log_rmse[i] - my);
  }
  return {sxy / sxx, 1.0 / std::sqrt(sxx)};
}

// The fitted slopes for both integrands, estimating with the `preceding`-th draw of each sample (0: dimensions
// 0-1; 3: a later, padded pair as the integrator's light-position draw sees it).
std::pair<Slope, Slope> measure(SamplerKind kind, int preceding) {
  constexpr int kRandomisations = 128;
  std::vector<double> log_n, log_smooth, log_disc, se_smooth, se_disc;
  for (int level = 4; level <= 12; ++level) {
    const uint32_t n = 1u << level;
    std::vector<double> e2_smooth, e2_disc;
    for (int m = 0; m < kRandomisations; ++m) {
      std::unique_ptr<Sampler> sampler = make_sampler(kind, mix_bits(uint64_t(level) << 32 | uint64_t(m)));
      double sum_smooth = 0, sum_disc = 0;
      for (uint32_t i = 0; i < n; ++i) {
        sampler->start_pixel_sample(0, 0, i);
        for (int d = 0; d < preceding; ++d) sampler->next_1d();
        const Vec2 p = sampler->next_2d();
        sum_smooth += smooth(p.x, p.y);
        sum_disc += disc(p.x, p.y);
      }
      const double es = sum_smooth / n - kSmoothIntegral, ed = sum_disc / n - kDiscIntegral;
      e2_smooth.push_back(es * es), e2_disc.push_back(ed * ed);
    }
    auto summarise = [&](const std::vector<double>& e2, std::vector<double>& log_rmse, std::vector<double>& se) {
      double mean = 0, var = 0;
      for (double v : e2) mean += v / kRandomisations;
      for (double v : e2) var += (v - mean) * (v - mean) / (kRandomisations - 1);
      log_rmse.push_back(0.5 * std::log(mean));
      se.push_back(0.5 * std::sqrt(var / kRandomisations) / mean);
    };
    log_n.push_back(std::log(double(n)));
    summarise(e2_smooth, log_smooth, se_smooth);
    summarise(e2_disc, log_disc, se_disc);
  }
  return {fit(log_n, log_smooth, se_smooth), fit(log_n, log_disc, se_disc)};
}

}  // namespace

TEST_CASE("Independent sampling converges as N^-1/2 on smooth and discontinuous integrands") {
  // Monte Carlo: RMSE = σ_f/√N exactly, so the slope is −½ up to the fit's noise; 4 standard errors.
  const auto [smooth_fit, disc_fit] = measure(SamplerKind::independent, 0);
  MESSAGE("independent slopes: smooth ", smooth_fit.slope, " ± ", smooth_fit.standard_error, ", disc ",
          disc_fit.slope, " ± ", disc_fit.standard_error);
  CHECK(std::fabs(smooth_fit.slope + 0.5) < 4.0 * smooth_fit.standard_error);
  CHECK(std::fabs(disc_fit.slope + 0.5) < 4.0 * disc_fit.standard_error);
}

TEST_CASE("Owen-scrambled Sobol points converge faster than N^-1/2, in the first and in a padded pair") {
  // Scrambled (0,m,2)-nets: variance O(N^-3 log N) for smooth integrands (Owen 1997, "Scrambled net variance for
  // integrals of smooth functions", Ann. Stat. 25), so RMSE ≈ N^-1.5 up to the log factor. For an indicator with
  // a curved boundary the variance is O(N^-1.5), the rate of stratified sampling of an edge in 2D (Mitchell 1996,
  // "Consequences of stratified sampling in graphics", SIGGRAPH), RMSE ≈ N^-0.75; He & Wang (2015, SIAM J. Numer.
  // Anal. 53) prove O(N^(-1-1/(2d-1))) for scrambled nets, RMSE N^-2/3 for d = 2. The assertions leave room for the
  // pre-asymptotic log factors but not for a −½ slope: the fitted slope plus 4 standard errors must lie below −1.2
  // (smooth) and below −0.65 (discontinuous; just short of the proven −2/3). Measured: about −1.41 and −0.74.
  for (int preceding : {0, 3}) {
    const auto [smooth_fit, disc_fit] = measure(SamplerKind::sobol, preceding);
    MESSAGE("sobol slopes (draw after ", preceding, " 1D draws): smooth ", smooth_fit.slope, " ± ",
            smooth_fit.standard_error, ", disc ", disc_fit.slope, " ± ", disc_fit.standard_error);
    CHECK(smooth_fit.slope + 4.0 * smooth_fit.standard_error < -1.2);
    CHECK(disc_fit.slope + 4.0 * disc_fit.standard_error < -0.65);
  }
}
