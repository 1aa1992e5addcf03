// Continuous spectra: Planck's law, tabulated interpolation (both sample() paths), CIE daylight.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/daylight.h"
#include "spectral/error.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "test_support.h"

using namespace rimu;

namespace {

// Four wavelengths with a dummy pdf, to call sample().
SampledWavelengths at(float a, float b, float c, float d) { return SampledWavelengths(Float4(a, b, c, d), Float4(1.0f)); }

// c2 = hc/k from the SI 2019 exact constants, m·K (written out here rather than taken from the code under test).
constexpr double kC2_mK = 6.62607015e-34 * 299792458.0 / 1.380649e-23;

}  // namespace

TEST_CASE("Planck's law at 5000 K, 500 nm") {
  // Reference computed by hand (40-digit decimal arithmetic) from the SI 2019 exact constants
  // h = 6.62607015e-34 J·s, c = 299792458 m/s, k = 1.380649e-23 J/K:
  //   x = hc/(λkT) = 5.7551075100157352..., L = 2hc²/λ⁵ / (eˣ − 1) · 1e-9 m/nm = 12107.1905903981 W/(m²·sr·nm).
  // Double evaluation of pow, expm1 and a few products: 1e-12 relative is ~100 ulp of headroom.
  CHECK(planck_radiance_w_m2_sr_nm(500.0, 5000.0) == doctest::Approx(12107.1905903981).epsilon(1e-12));
  // Outside its domain the function is zero rather than NaN.
  CHECK(planck_radiance_w_m2_sr_nm(0.0, 5000.0) == 0.0);
  CHECK(planck_radiance_w_m2_sr_nm(500.0, 0.0) == 0.0);
}

TEST_CASE("Wien's displacement law: the peak is at b/T") {
  // b = c2 / x_w with x_w the root of x = 5(1 − e^(−x)) (maximum of x⁵/(eˣ − 1)); solved here by fixed-point
  // iteration (contraction factor 5e^(−5) ≈ 0.03, so 40 steps converge far past double precision).
  double x_w = 5.0;
  for (int i = 0; i < 40; ++i) x_w = 5.0 * (1.0 - std::exp(-x_w));
  const double b_mK = kC2_mK / x_w;
  CHECK(b_mK == doctest::Approx(2.897771955e-3).epsilon(1e-9));  // CODATA 2018 Wien wavelength constant
  for (const double t_k : {1500.0, 2856.0, 5000.0, 6504.0, 20000.0}) {
    CAPTURE(t_k);
    const double peak_nm = b_mK / t_k * 1e9;
    // Near the peak L falls off quadratically, by ~(δ/λ)² · 12 relative for a step δ; 1e-4 of the peak wavelength
    // gives a drop of ~1e-7, far above double rounding, so both neighbours must be strictly lower.
    const double step_nm = 1e-4 * peak_nm;
    const double l_peak = planck_radiance_w_m2_sr_nm(peak_nm, t_k);
    CHECK(planck_radiance_w_m2_sr_nm(peak_nm - step_nm, t_k) < l_peak);
    CHECK(planck_radiance_w_m2_sr_nm(peak_nm + step_nm, t_k) < l_peak);
  }
}

TEST_CASE("Stefan-Boltzmann law: π ∫ L dλ = σT⁴ up to the truncated tail") {
  // σ = 2π⁵k⁴/(15h³c²) = 5.670374419e-8 W/(m²·K⁴) (CODATA 2018, exact constants, 10 digits).
  constexpr double kSigma = 5.670374419e-8;
  const double t_k = 5000.0;
  const double lo_nm = 10.0, hi_nm = 1.0e5;
  // Simpson's rule in u = ln λ (∫ L dλ = ∫ L λ du): the integrand is smooth and spans many decades of λ.
  const int n = 20000;  // even
  const double u0 = std::log(lo_nm), h = (std::log(hi_nm) - u0) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double lambda_nm = std::exp(u0 + i * h);
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += weight * planck_radiance_w_m2_sr_nm(lambda_nm, t_k) * lambda_nm;
  }
  const double exitance_w_m2 = std::numbers::pi * sum * h / 3.0;
  // The fraction of σT⁴ beyond λ_hi is (15/π⁴) ∫₀^x₀ x³/(eˣ − 1) dx with x₀ = c2/(λ_hi T) = 0.0288, whose series
  // is (15/π⁴)(x₀³/3 − x₀⁴/8 + x₀⁵/60 − ...) ≈ 1.2e-6; below 10 nm, x₀ = 288 and the fraction is ~e^(−288).
  // With the tail accounted for, what remains is Simpson's error and rounding (well below 1e-10) and the
  // next series term x₀⁷/5040 (~1e-15); 1e-9 relative is a safe bound that still catches a wrong constant.
  const double x0 = kC2_mK / (hi_nm * 1e-9 * t_k);
  const double tail = 15.0 / std::pow(std::numbers::pi, 4) *
                      (x0 * x0 * x0 / 3.0 - std::pow(x0, 4) / 8.0 + std::pow(x0, 5) / 60.0);
  CHECK(tail > 1e-6);  // the correction is real: without it the check below would fail
  CHECK(exitance_w_m2 / (kSigma * std::pow(t_k, 4)) == doctest::Approx(1.0 - tail).epsilon(1e-9));
}

TEST_CASE("CIE illuminant A is Planck's law at 2848 K with c2 = 1.435e-2 m·K") {
  // CIE 15:2004 eq. 3.1 defines S_A(λ) = 100 (560/λ)⁵ (e^(c2'/(2848·560 nm)) − 1)/(e^(c2'/(2848 λ)) − 1) with
  // c2' = 1.435e-2 m·K. Planck's law depends on c2/T only, so with the exact c2 that is T = 2848 c2/c2'.
  // The tabulated A (CIE 15:2004 Table T.1, 1 nm) has 6 significant digits: each value must lie within half a
  // unit of its 6th digit.
  const BlackbodySpectrum planck(2848.0 * kC2_mK / 1.435e-2, BlackbodySpectrum::Scale::absolute_radiance);
  const auto table_a = test::library().illuminant("A");
  const auto& knots = dynamic_cast<const TabulatedSpectrum&>(*table_a);
  const double at_560 = planck.value(560.0);
  for (size_t i = 0; i < knots.wavelengths_nm().size(); ++i) {
    const double lambda_nm = knots.wavelengths_nm()[i], a = knots.values()[i];
    const double half_unit = 0.5 * std::pow(10.0, std::floor(std::log10(a)) - 5.0);
    CAPTURE(lambda_nm);
    CHECK(std::abs(100.0 * planck.value(lambda_nm) / at_560 - a) <= half_unit);
  }
}

TEST_CASE("blackbody scaled to peak one") {
  for (const double t_k : {3000.0, 5000.0, 6504.0, 10000.0}) {
    CAPTURE(t_k);
    const BlackbodySpectrum shape(t_k, BlackbodySpectrum::Scale::peak_one);
    const BlackbodySpectrum absolute(t_k, BlackbodySpectrum::Scale::absolute_radiance);
    const double peak_nm = 2.897771955e-3 / t_k * 1e9;
    CHECK(shape.value(peak_nm) == doctest::Approx(1.0).epsilon(1e-14));
    // Same shape: the ratio to the absolute radiance is one constant (1/L(peak)).
    const double scale = 1.0 / absolute.value(peak_nm);
    for (double l = 300.0; l <= 2000.0; l += 7.3) {
      CHECK(shape.value(l) <= 1.0 + 1e-14);
      CHECK(shape.value(l) == doctest::Approx(scale * absolute.value(l)).epsilon(1e-13));
    }
  }
  // max_value() bounds value() over 360-830 nm even when the peak is outside (2000 K peaks at 1449 nm).
  const BlackbodySpectrum warm(2000.0, BlackbodySpectrum::Scale::peak_one);
  CHECK(warm.max_value() == doctest::Approx(warm.value(830.0)).epsilon(1e-14));
  CHECK(warm.max_value() < 1.0);
  CHECK_THROWS_AS(BlackbodySpectrum(0.0, BlackbodySpectrum::Scale::peak_one), InputError);
  CHECK_THROWS_AS(BlackbodySpectrum(std::nan(""), BlackbodySpectrum::Scale::peak_one), InputError);
  CHECK_THROWS_AS(BlackbodySpectrum(2e6, BlackbodySpectrum::Scale::peak_one), InputError);
}

TEST_CASE("tabulated spectrum: linear interpolation and extrapolation") {
  const TabulatedSpectrum zero({400.0, 410.0, 430.0}, {1.0, 3.0, -1.0}, Extrapolation::zero, "zero");
  const TabulatedSpectrum clamp({400.0, 410.0, 430.0}, {1.0, 3.0, -1.0}, Extrapolation::clamp, "clamp");
  for (const TabulatedSpectrum* s : {&zero, &clamp}) {
    CHECK(s->value(400.0) == 1.0);  // at knots: exactly the tabulated value
    CHECK(s->value(410.0) == 3.0);
    CHECK(s->value(430.0) == -1.0);
    CHECK(s->value(405.0) == doctest::Approx(2.0).epsilon(1e-15));  // halfway 1 → 3
    CHECK(s->value(420.0) == doctest::Approx(1.0).epsilon(1e-15));  // halfway 3 → −1
    CHECK(s->value(427.5) == doctest::Approx(-0.5).epsilon(1e-15));
  }
  CHECK(zero.value(399.99) == 0.0);
  CHECK(zero.value(430.01) == 0.0);
  CHECK(zero.value(std::nan("")) == 0.0);
  CHECK(clamp.value(300.0) == 1.0);
  CHECK(clamp.value(900.0) == -1.0);
  // The bounds include 0 for zero extrapolation (the value outside the knots).
  CHECK(zero.max_value() == 3.0);
  CHECK(zero.min_value() == -1.0);
  CHECK(TabulatedSpectrum({400.0, 410.0}, {2.0, 3.0}, Extrapolation::zero, "").min_value() == 0.0);
  CHECK(TabulatedSpectrum({400.0, 410.0}, {2.0, 3.0}, Extrapolation::clamp, "").min_value() == 2.0);

  CHECK_THROWS_AS(TabulatedSpectrum({400.0, 410.0}, {1.0}, Extrapolation::zero, "sizes"), InputError);
  CHECK_THROWS_AS(TabulatedSpectrum({400.0}, {1.0}, Extrapolation::zero, "one sample"), InputError);
  CHECK_THROWS_AS(TabulatedSpectrum({400.0, 400.0}, {1.0, 2.0}, Extrapolation::zero, "repeat"), InputError);
  CHECK_THROWS_AS(TabulatedSpectrum({400.0, 410.0}, {1.0, INFINITY}, Extrapolation::zero, "inf"), InputError);
}

namespace {

// |sample() − value()| over the knots, the ends of 360-830 nm and 2000 random sets of four wavelengths.
// The 1 nm copy is stored as float and interpolated in float (λ − 360 is exact in float over this range), so the
// difference is a few float roundings of the neighbouring values: 4 · 2⁻²⁴ · max|value| bounds it.
void check_sample_matches_value(const Spectrum& s, std::uint32_t seed) {
  CAPTURE(s.describe());
  const double bound = 4.0 * std::ldexp(1.0, -24) * std::max(s.max_value(), 1.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> lambda(360.0f, 830.0f);
  std::vector<SampledWavelengths> cases = {at(360.0f, 400.0f, 410.0f, 829.999f), at(430.0f, 555.0f, 399.5f, 430.5f),
                                           at(379.5f, 380.0f, 780.0f, 780.5f)};
  for (int i = 0; i < 2000; ++i) cases.push_back(at(lambda(rng), lambda(rng), lambda(rng), lambda(rng)));
  int reported = 0;
  for (const SampledWavelengths& w : cases) {
    const Float4 fast = s.sample(w);
    for (int lane = 0; lane < kLaneCount; ++lane) {
      const double exact = s.value(double(w.lambda_nm(lane)));
      if (std::abs(fast[lane] - exact) > bound && reported++ < 5) {  // report the first few only
        CAPTURE(w.lambda_nm(lane));
        CHECK(fast[lane] == doctest::Approx(exact));
      }
    }
  }
  CHECK(reported == 0);
}

}  // namespace

TEST_CASE("tabulated spectrum: the dense 1 nm sample() path equals value()") {
  // Knots on whole nm take the dense path. Tables that cover 360-830 nm, and any table with clamp extrapolation,
  // are continuous there, so the 1 nm copy is the same piecewise-linear function.
  const Observer& observer = test::library().observer(StandardObserver::cie1931_2deg);
  check_sample_matches_value(observer.y_bar, 1);
  check_sample_matches_value(observer.z_bar, 2);
  check_sample_matches_value(*test::library().illuminant("D65"), 3);  // 300-830 nm: wider than the dense range
  check_sample_matches_value(
      TabulatedSpectrum({400.0, 410.0, 430.0}, {1.0, 3.0, -1.0}, Extrapolation::clamp, "short clamp"), 4);
}

TEST_CASE("tabulated spectrum: the dense path at the ends of a zero-extrapolated table inside 360-830 nm") {
  // Regression: with zero extrapolation and knots that end inside 360-830 nm (every 380-780 nm CIE table: F,
  // FL3, HP, LED), value() steps from 0 to S(first knot) at the first knot, while the 1 nm copy holds 0 at the
  // whole nm before it; sample() once ramped over that nanometre (~S(380)/2 at 379.5 nm). It now masks lanes
  // outside [first, last knot] to zero.
  check_sample_matches_value(
      TabulatedSpectrum({400.0, 410.0, 430.0}, {1.0, 3.0, -1.0}, Extrapolation::zero, "short zero"), 5);
  check_sample_matches_value(*test::library().illuminant("F2"), 6);
}

TEST_CASE("tabulated spectrum: the search path for non-integer knots agrees with value()") {
  // pbrt's metal tables sit on an even photon-energy grid (298.757, 302.400, ... nm): no dense copy, so
  // sample() falls back to value() per lane and must equal it rounded to float.
  const CsvTable& table = test::library().table("spectra/materials/pbrt_metal_au_nk.csv");
  const TabulatedSpectrum k = TabulatedSpectrum::from_csv(table, "k", Extrapolation::clamp);
  // Between the first two knots, by hand: k = 1.920375 + t (1.920000 − 1.920375), t = (300 − 298.75705)/3.643371.
  const double t = (300.0 - 298.75705) / (302.400421 - 298.75705);
  CHECK(k.value(300.0) == doctest::Approx(1.920375 + t * (1.920000 - 1.920375)).epsilon(1e-15));
  CHECK(k.value(298.75705) == 1.920375);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> lambda(360.0f, 830.0f);
  for (int i = 0; i < 1000; ++i) {
    const SampledWavelengths w = at(lambda(rng), lambda(rng), lambda(rng), lambda(rng));
    const Float4 sampled = k.sample(w);
    for (int lane = 0; lane < kLaneCount; ++lane) CHECK(sampled[lane] == float(k.value(w.lambda_nm(lane))));
  }
}

TEST_CASE("CIE daylight from S0, S1, S2 reproduces the tabulated D65 and D50") {
  // CIE 15:2004 §3.1: the D illuminants are S0 + M1 S1 + M2 S2 at CCT 6500·1.4388/1.4380 K (resp. 5000·...),
  // the correction for the change of c2 since they were defined, with M1, M2 rounded to 3 decimals. The
  // tabulated D65/D50 (Table T.1) then agree to ≤ 0.001 at every 5 nm point of 300-830 nm (data/README.md,
  // "Checks"; the tables' own rounding, worst 0.00085 for D65 at 545 nm). Unrounded M1, M2 differ by up to
  // 0.016, which is why the rounding is an option.
  struct Row {
    const char* name;
    double nominal_cct_k;
  };
  for (const Row row : {Row{"D65", 6500.0}, Row{"D50", 5000.0}}) {
    CAPTURE(row.name);
    const double cct_k = row.nominal_cct_k * 1.4388 / 1.4380;
    const auto table = test::library().illuminant(row.name);
    const TabulatedSpectrum rounded =
        daylight_spectrum(test::library().daylight_basis(), cct_k, DaylightRounding::cie_three_decimals);
    const TabulatedSpectrum exact = daylight_spectrum(test::library().daylight_basis(), cct_k, DaylightRounding::exact);
    double worst_rounded = 0.0, worst_exact = 0.0;
    for (double l = 300.0; l <= 830.0; l += 5.0) {
      worst_rounded = std::max(worst_rounded, std::abs(rounded.value(l) - table->value(l)));
      worst_exact = std::max(worst_exact, std::abs(exact.value(l) - table->value(l)));
    }
    CHECK(worst_rounded <= 0.001);
    CHECK(worst_exact > 0.001);
    CHECK(rounded.value(560.0) == doctest::Approx(100.0).epsilon(1e-4));  // normalised near 100 at 560 nm
  }
}

TEST_CASE("daylight chromaticity: valid 4000-25000 K, continuous at 7000 K") {
  CHECK_NOTHROW(daylight_chromaticity(4000.0));
  CHECK_NOTHROW(daylight_chromaticity(25000.0));
  for (const double bad : {3999.9, 25000.1, 0.0, -6500.0, std::nan(""), double(INFINITY)}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(daylight_chromaticity(bad), InputError);
    CHECK_THROWS_AS(daylight_spectrum(test::library().daylight_basis(), bad), InputError);
  }
  // CIE 15:2004 eq. 3.3 has two cubic branches meeting at 7000 K; with coefficients given to 4-5 figures they
  // meet to ~1e-6 in x. A mistyped coefficient would break that by far more than 1e-5.
  const Chromaticity below = daylight_chromaticity(7000.0);
  const Chromaticity above = daylight_chromaticity(std::nextafter(7000.0, 8000.0));
  CHECK(std::abs(below.x - above.x) < 1e-5);
  // eq. 3.4: y = −3x² + 2.87x − 0.275 for every CCT.
  for (const double cct_k : {4000.0, 5003.0, 6504.0, 9000.0, 25000.0}) {
    const Chromaticity c = daylight_chromaticity(cct_k);
    CHECK(c.y == doctest::Approx(-3.0 * c.x * c.x + 2.870 * c.x - 0.275).epsilon(1e-14));
  }
  // At D65's CCT the equation's x matches the x of D65 in CIE 15:2004 Table T.3, 0.31272 (5 decimals, ±5e-6).
  // (Its y, 0.32913, is 1e-4 from T.3's 0.32903: eq. 3.4 is a fit to measured daylight, not exact for D65.)
  CHECK(std::abs(daylight_chromaticity(6500.0 * 1.4388 / 1.4380).x - 0.31272) <= 5e-6);
}
