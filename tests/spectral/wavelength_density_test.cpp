// The tabulated wavelength density: normalisation, inverse CDF against the pdf (chi-square), zero bins, the rotated
// partners, the light-weighted mixture, hard inputs, and the variance it removes under a line spectrum.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/wavelengths/wavelength_density.h"
#include "spectral/colorimetry/light_weighted_wavelength_density.h"
#include "spectral/wavelengths/wavelength_range.h"
#include "statistics.h"
#include "test_support.h"

using namespace rimu;
using test::uniform01;

namespace {

constexpr int kBins = TabulatedWavelengthDensity::kBins;

const Observer& cie1931() { return test::library().observer(StandardObserver::cie1931_2deg); }

// F11 through the CIE 1931 curves with the default defensive share: three narrow lines and a low floor.
TabulatedWavelengthDensity f11_density(double defensive) {
  const SpectrumPtr f11 = test::library().illuminant("F11");
  return light_weighted_wavelength_density([&](double nm) { return f11->value(nm); }, cie1931(), defensive);
}

// The emission part of light_weighted_wavelength_density written out independently: over 1 nm bin means at
// quarter-nm points, (1/3) Σ_c S r_c / ∫ S r_c.
std::vector<double> emission_part(const Spectrum& s) {
  const TabulatedSpectrum* curves[3] = {&cie1931().x_bar, &cie1931().y_bar, &cie1931().z_bar};
  std::vector<std::vector<double>> per_channel(3, std::vector<double>(kBins, 0.0));
  double totals[3] = {0, 0, 0};
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kBins; ++i) {
      for (int q = 0; q < 4; ++q) {
        const double nm = kLambdaMinNm + i + (q + 0.5) / 4.0;
        per_channel[size_t(c)][size_t(i)] += s.value(nm) * curves[c]->value(nm);
      }
      totals[c] += per_channel[size_t(c)][size_t(i)];
    }
  std::vector<double> part(kBins, 0.0);
  for (int i = 0; i < kBins; ++i)
    for (int c = 0; c < 3; ++c) part[size_t(i)] += per_channel[size_t(c)][size_t(i)] / totals[c] / 3.0;
  return part;
}

double visible_bin_mass(int i) {
  double v = 0.0, total = 0.0;
  for (int b = 0; b < kBins; ++b)
    for (int q = 0; q < 4; ++q) {
      const double p = visible_wavelength_pdf(float(kLambdaMinNm + b + (q + 0.5) / 4.0));
      total += p;
      if (b == i) v += p;
    }
  return v / total;
}

}  // namespace

TEST_CASE("tabulated wavelength density: normalised, pdf per bin, zero bins never sampled") {
  std::vector<double> weights(kBins, 1.0);
  for (int i = 140; i < 240; ++i) weights[size_t(i)] = 0.0;  // no density on 500-600 nm
  weights[50] = 37.0;                                       // one spike at 410-411 nm
  const TabulatedWavelengthDensity d(weights);
  double total = 0.0;
  for (int i = 0; i < kBins; ++i) total += d.pdf(float(kLambdaMinNm) + float(i) + 0.5f);
  CHECK(total == doctest::Approx(1.0).epsilon(1e-6));
  CHECK(d.pdf(410.5f) == doctest::Approx(37.0 / (370.0 + 37.0 - 1.0)).epsilon(1e-5));
  CHECK(d.pdf(550.0f) == 0.0f);
  CHECK(d.pdf(359.9f) == 0.0f);
  CHECK(d.pdf(830.0f) == 0.0f);
  CHECK(d.pdf(std::numeric_limits<float>::quiet_NaN()) == 0.0f);
  // Every u, including the ends, maps into [360, 830) with positive density, monotonically.
  float previous = 0.0f;
  for (int k = 0; k <= 100000; ++k) {
    const float u = k == 100000 ? std::nextafter(1.0f, 0.0f) : float(k) / 100000.0f;
    const float l = d.sample(u);
    REQUIRE(l >= float(kLambdaMinNm));
    REQUIRE(l < float(kLambdaMaxNm));
    REQUIRE(d.pdf(l) > 0.0f);
    REQUIRE(l >= previous);
    previous = l;
  }
}

TEST_CASE("tabulated wavelength density: samples follow the pdf (chi-square per lane), partners are rotations") {
  // F11's lines make a hard case: 1 nm bins of very different mass. 2e5 samples, one cell per 1 nm bin, adjacent
  // pooling to ≥ 5 expected counts; p > 1e-3 per lane (four lanes: family-wise false alarm < 0.4 %).
  const TabulatedWavelengthDensity d = f11_density(0.25);
  constexpr int kSamples = 200000;
  std::vector<double> expected(kBins), uniform_expected(kBins, double(kSamples) / kBins);
  for (int i = 0; i < kBins; ++i) expected[size_t(i)] = kSamples * double(d.pdf(float(kLambdaMinNm) + float(i) + 0.5f));
  std::vector<std::vector<double>> observed(kLaneCount, std::vector<double>(kBins, 0.0));
  std::mt19937 rng(1995);
  for (int n = 0; n < kSamples; ++n) {
    const float u = uniform01(rng);
    const SampledWavelengths w = d.sample_wavelengths(u);
    for (int j = 0; j < kLaneCount; ++j) {
      float u_lane = u + float(j) / kLaneCount;  // written out, not rotated_primary_sample: the test's own copy
      if (u_lane >= 1.0f) u_lane -= 1.0f;
      REQUIRE(w.lambda_nm(j) == d.sample(u_lane));
      REQUIRE(w.pdf()[j] == d.pdf(w.lambda_nm(j)));
      observed[size_t(j)][size_t(int(w.lambda_nm(j) - float(kLambdaMinNm)))] += 1.0;
    }
  }
  for (int j = 0; j < kLaneCount; ++j) {
    CAPTURE(j);
    const test::ChiSquareResult r = test::pearson_chi_square(observed[size_t(j)], expected, test::Pooling::adjacent);
    CAPTURE(r.statistic);
    CAPTURE(r.degrees_of_freedom);
    CHECK(r.p_value > 1e-3);
    // The counts are wildly inconsistent with the visible density's shape as a uniform one: the test has teeth.
    CHECK(test::pearson_chi_square(observed[size_t(j)], uniform_expected, test::Pooling::adjacent).p_value < 1e-12);
  }
}

TEST_CASE("light-weighted density: the mixture formula, the visible limit, black and bad emission") {
  // m = 1 is the visible density, up to averaging it over each 1 nm bin: its relative curvature is ≤ 4a² ≈ 2e-4
  // per nm² (a = 0.0072/nm), so a bin mean differs from the centre value by < 1e-5 relative; 1e-4 allows float.
  const TabulatedWavelengthDensity visible =
      light_weighted_wavelength_density([](double) { return 1.0; }, cie1931(), 1.0);
  for (float nm : {360.5f, 420.5f, 538.5f, 700.5f, 829.5f})
    CHECK(visible.pdf(nm) == doctest::Approx(visible_wavelength_pdf(nm)).epsilon(1e-4));
  // The mixture, (1 − m)·(1/3)Σ_c S r_c/∫S r_c + m·p_vis, against the formula written out here; under F11 (lines)
  // and under CIE A, whose Z integrand is small and blue but still gets a third of the emission part.
  for (const char* name : {"F11", "A"}) {
    CAPTURE(name);
    const SpectrumPtr light = test::library().illuminant(name);
    const TabulatedWavelengthDensity d =
        light_weighted_wavelength_density([&](double nm) { return light->value(nm); }, cie1931(), 0.25);
    const std::vector<double> part = emission_part(*light);
    for (int bin : {40, 75, 184, 251, 340, 460}) {
      CAPTURE(bin);
      CHECK(d.pdf(float(kLambdaMinNm) + float(bin) + 0.5f) ==
            doctest::Approx(0.75 * part[size_t(bin)] + 0.25 * visible_bin_mass(bin)).epsilon(1e-5));
    }
  }
  // Under A the emission part puts a third of its mass in Z's integrand: more density at 450 nm than S·(x̄+ȳ+z̄)
  // alone would, whose blue share A's red-heavy spectrum shrinks.
  {
    const SpectrumPtr a = test::library().illuminant("A");
    const std::vector<double> part = emission_part(*a);
    double z_share = 0.0, unbalanced_z = 0.0, unbalanced_total = 0.0;
    for (int i = 0; i < kBins; ++i) {
      const double nm = kLambdaMinNm + i + 0.5;
      if (nm < 500.0) z_share += part[size_t(i)];
      const double u = a->value(nm) * (cie1931().x_bar.value(nm) + cie1931().y_bar.value(nm) + cie1931().z_bar.value(nm));
      unbalanced_total += u;
      if (nm < 500.0) unbalanced_z += u;
    }
    CHECK(z_share > 1.3 * unbalanced_z / unbalanced_total);
  }
  const TabulatedWavelengthDensity d = f11_density(0.25);
  // Nowhere below the defensive share of the visible density.
  for (int i = 0; i < kBins; ++i) {
    const float nm = float(kLambdaMinNm) + float(i) + 0.5f;
    REQUIRE(d.pdf(nm) >= 0.25f * visible.pdf(nm) * (1.0f - 1e-4f));
  }
  // Black, NaN, infinite and negative emission is no emission: the visible density.
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double bad : {0.0, nan, inf, -1.0}) {
    CAPTURE(bad);
    const TabulatedWavelengthDensity b =
        light_weighted_wavelength_density([&](double) { return bad; }, cie1931(), 0.25);
    CHECK(b.pdf(500.5f) == doctest::Approx(visible.pdf(500.5f)).epsilon(1e-6));
  }
}

TEST_CASE("light-weighted density under F11: ∫ F11·ȳ dλ unbiased, with far less variance than the visible density") {
  // The direct-lighting integrand of a grey surface under F11 seen through ȳ. Four-lane estimates (hero + rotations)
  // with 2e4 independent u: both means within 5 standard errors of the 1 nm sum (false failure ~6e-7 each).
  const SpectrumPtr f11 = test::library().illuminant("F11");
  const Observer& observer = test::library().observer(StandardObserver::cie1931_2deg);
  // Both tables are linear between integer-nm knots, so their product is quadratic on each 1 nm interval and
  // Simpson's rule on 0.5 nm steps integrates it exactly (up to rounding).
  const double exact = test::simpson([&](double nm) { return f11->value(nm) * observer.y_bar.value(nm); }, kLambdaMinNm,
                                     kLambdaMaxNm, 2 * kBins);
  const TabulatedWavelengthDensity lights = f11_density(0.25);
  auto estimate = [&](auto&& sample_lanes, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<double> values;
    for (int n = 0; n < 20000; ++n) {
      const SampledWavelengths w = sample_lanes(uniform01(rng));
      double f = 0.0;
      for (int j = 0; j < kLaneCount; ++j)
        f += f11->value(w.lambda_nm(j)) * observer.y_bar.value(w.lambda_nm(j)) / w.pdf()[j] / kLaneCount;
      values.push_back(f);
    }
    return test::mean_and_standard_error(values);
  };
  const auto [visible_mean, visible_se] = estimate([](float u) { return SampledWavelengths::sample_visible(u); }, 7);
  const auto [lights_mean, lights_se] = estimate([&](float u) { return lights.sample_wavelengths(u); }, 8);
  CAPTURE(visible_se);
  CAPTURE(lights_se);
  CHECK(std::fabs(visible_mean - exact) <= 5.0 * visible_se);
  CHECK(std::fabs(lights_mean - exact) <= 5.0 * lights_se);
  // What the density is for: under F11's lines the visible density's weights are spiky. The lights density must
  // at least halve the standard error (measured: see docs/sampling.md); a density that ignored S would not.
  CHECK(lights_se < 0.5 * visible_se);
}
