// The thin dielectric sheet: its reflectance against the closed form, R + T = 1, straight transmission, and
// sample weights and lobe probabilities that agree with what it reports.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "bsdf_test_fixtures.h"
#include "spectral/error.h"
#include "test_support.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/bsdfs/fresnel.h"
#include "transport/bsdfs/material.h"

using namespace rimu;

namespace {

// r_s² and r_p² of an interface into index η from index 1 (Born & Wolf §1.5.2), written out here independently of
// transport/bsdfs/fresnel.cpp.
struct SP {
  double s, p;
};
SP polarised_reflectance(double cos_i, double eta) {
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return {1.0, 1.0};
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t), rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return {rs * rs, rp * rp};
}

// The incoherent slab's R and T for one polarisation of single-face reflectance r0 and one-pass transmittance τ.
SP slab(double r0, double tau) {
  const double t0 = 1.0 - r0, d = 1.0 - r0 * r0 * tau * tau;
  return {r0 + t0 * t0 * r0 * tau * tau / d, t0 * t0 * tau / d};
}

// Unpolarised light is half s, half p; each polarisation's series is summed on its own.
SP sheet_reflectance_transmittance(double cos_i, double eta, double tau) {
  const SP r0 = polarised_reflectance(cos_i, eta);
  const SP s = slab(r0.s, tau), p = slab(r0.p, tau);
  return {0.5 * (s.s + p.s), 0.5 * (s.p + p.p)};
}

Vec3 direction(float cos_theta) {
  const float s = std::sqrt(std::fmax(0.0f, 1.0f - cos_theta * cos_theta));
  return {s * std::cos(0.4f), s * std::sin(0.4f), cos_theta};
}

}  // namespace

TEST_CASE("thin dielectric: at normal incidence R = 2R0/(1 + R0), the closed form of the inter-reflection series") {
  // η = 1.5: R₀ = ((η−1)/(η+1))² = 0.04; the series R₀ + (1−R₀)²R₀/(1−R₀²) sums to 2R₀/(1+R₀) = 0.0769231
  // (e.g. Hecht, Optics, for an incoherent slab).
  const ThinDielectricBsdf sheet(Float4(1.5f));
  const double r0 = 0.04;
  CHECK(sheet.reflectance(1.0f)[0] == doctest::Approx(2 * r0 / (1 + r0)).epsilon(1e-6));
  // η = 1 is no sheet at all: nothing reflected.
  CHECK(ThinDielectricBsdf(Float4(1.0f)).reflectance(0.5f)[0] == doctest::Approx(0.0).epsilon(1e-7));
  // Grazing: everything reflected (R₀ → 1), finite.
  CHECK(sheet.reflectance(0.0f)[0] == 1.0f);
}

TEST_CASE("thin dielectric: the series is summed per polarisation (a clear pane at 60° and 70° transmits 0.848, 0.729)") {
  // η = 1.5. Per polarisation at 60°: r_s² = 0.17657, r_p² = 0.00180, so T = ½((1 − r_s²)/(1 + r_s²) + (1 − r_p²)/(1 +
  // r_p²)) = 0.84813; averaging r² first would give (1 − 0.08919)/(1 + 0.08919) = 0.83623. At 70°: 0.72871 against
  // 0.70788. Radiance's glass material and optics texts treat the polarisations apart; pbrt-v4 averages first.
  const ThinDielectricBsdf sheet(Float4(1.5f));
  const double c60 = 0.5, c70 = std::cos(70.0 * std::numbers::pi / 180.0);
  CHECK(sheet.straight_through(float(c60)).transmittance[0] == doctest::Approx(0.84813).epsilon(2e-5));
  CHECK(sheet.straight_through(float(c70)).transmittance[0] == doctest::Approx(0.72871).epsilon(2e-5));
  CHECK(sheet.straight_through(float(c60)).transmittance[0] ==
        doctest::Approx(sheet_reflectance_transmittance(c60, 1.5, 1.0).p).epsilon(1e-5));
}

TEST_CASE("thin dielectric: a lossless sheet reflects R and transmits 1 - R, per lane, from either side") {
  const SampledWavelengths lambda = test::four_visible_wavelengths();
  const Float4 eta = test::bk7_eta(lambda);  // a different index per lane
  const ThinDielectricBsdf sheet(eta);
  for (float c : {1.0f, 0.8f, 0.5f, 0.2f, 0.05f, -0.7f, -0.1f}) {
    CAPTURE(c);
    const Vec3 wo = direction(c);
    const auto reflected = sheet.sample(wo, 0.0f, {0.5f, 0.5f});
    const auto transmitted = sheet.sample(wo, 0.999999f, {0.5f, 0.5f});
    REQUIRE(reflected);
    REQUIRE(transmitted);
    CHECK(reflected->is_delta);
    CHECK(transmitted->is_delta);
    CHECK_FALSE(transmitted->wavelength_dependent_direction);
    // Mirror direction, and straight through: the two refractions cancel.
    CHECK(reflected->wi.z == doctest::Approx(c));
    CHECK(reflected->wi.x == doctest::Approx(-wo.x));
    CHECK(transmitted->wi.x == -wo.x);
    CHECK(transmitted->wi.y == -wo.y);
    CHECK(transmitted->wi.z == -wo.z);
    for (int lane = 0; lane < 4; ++lane) {
      CAPTURE(lane);
      // Analytic R per lane in double: R₀ + T₀²R₀/(1 − R₀²) per polarisation, averaged.
      const double r = sheet_reflectance_transmittance(std::fabs(c), double(eta[lane]), 1.0).s;
      const double r_sheet = reflected->f[lane] * std::fabs(c);
      const double t_sheet = transmitted->f[lane] * std::fabs(c);
      CHECK(r_sheet == doctest::Approx(r).epsilon(1e-5));
      CHECK(r_sheet + t_sheet == doctest::Approx(1.0).epsilon(1e-6));  // lossless: R + T = 1
      // The probability of each lobe is its reflectance: the weights are 1 in the lane that chose.
      CHECK(reflected->pdf[lane] == doctest::Approx(r_sheet).epsilon(1e-6));
      CHECK(transmitted->pdf[lane] == doctest::Approx(t_sheet).epsilon(1e-6));
    }
    CHECK(reflected->hero_weight()[0] == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(transmitted->hero_weight()[0] == doctest::Approx(1.0).epsilon(1e-6));
    // Delta lobes only: nothing to evaluate.
    CHECK((sheet.eval(wo, reflected->wi) == Float4(0.0f)).all());
    CHECK((sheet.pdf(wo, transmitted->wi) == Float4(0.0f)).all());
  }
  CHECK_FALSE(sheet.sample({1.0f, 0.0f, 0.0f}, 0.5f, {0.5f, 0.5f}));  // on the horizon
}

TEST_CASE("thin dielectric: the fraction of samples reflected is R(hero), and the mean weight is 1") {
  const Float4 eta = test::bk7_eta(test::four_visible_wavelengths());
  const Bsdf sheet = ThinDielectricBsdf(eta);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float c : {0.9f, 0.3f, -0.6f}) {
    CAPTURE(c);
    const Vec3 wo = direction(c);
    constexpr int kCount = 200000;
    int reflections = 0;
    double weight = 0;
    for (int i = 0; i < kCount; ++i) {
      const auto s = sheet.sample(wo, u(rng), {u(rng), u(rng)});
      REQUIRE(s);
      reflections += s->wi.z * wo.z > 0.0f;
      weight += s->hero_weight()[0];
    }
    const double r = ThinDielectricBsdf(eta).reflectance(std::fabs(c))[0];
    // Binomial: 4σ with σ = √(R(1−R)/N).
    CHECK(std::fabs(double(reflections) / kCount - r) < 4.0 * std::sqrt(r * (1 - r) / kCount));
    CHECK(weight / kCount == doctest::Approx(1.0).epsilon(1e-5));  // every weight is 1: no energy lost or made
  }
}

TEST_CASE("thin dielectric material: a BK7 pane colours R and T but keeps one direction, and bad indices throw") {
  const SampledWavelengths lambda = test::four_visible_wavelengths();
  const Material pane = ThinDielectricMaterial(dielectric_ior(test::library(), "bk7"));
  const Bsdf bsdf = pane.bsdf({}, lambda);
  CHECK(bsdf.flags().has_transmission);
  CHECK(bsdf.flags().has_delta);
  CHECK_FALSE(bsdf.flags().has_non_delta);
  const auto s = bsdf.sample(direction(0.5f), 0.99f, {0.5f, 0.5f});
  REQUIRE(s);
  CHECK(s->pdf[1] > 0.0f);  // every lane shares the transmitted direction
  CHECK(s->pdf[0] != s->pdf[3]);  // BK7 disperses: the lanes' transmittances differ
  CHECK_THROWS_AS(ThinDielectricMaterial(nullptr), InputError);
  CHECK_THROWS_AS(ThinDielectricMaterial(std::make_shared<ConstantSpectrum>(0.0)), InputError);
}

TEST_CASE("thin dielectric: a tinted sheet absorbs by Beer-Lambert along its refracted path, and reports its lobes") {
  // τ = τₙ^(1/cos θt); R = R₀ + T₀²R₀τ²/(1 − R₀²τ²), T = T₀²τ/(1 − R₀²τ²) (the incoherent slab with absorption),
  // per polarisation, averaged.
  const Float4 eta(1.5f);
  const Float4 tau_n(0.2f, 0.9f, 0.5f, 1.0f);
  const ThinDielectricBsdf tinted(eta, tau_n);
  const ThinDielectricBsdf clear(eta);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float c : {1.0f, 0.7f, 0.3f, -0.5f}) {
    CAPTURE(c);
    const double cos_i = std::fabs(c);
    const double cos_t = std::sqrt(1.0 - (1.0 - cos_i * cos_i) / 2.25);
    const ThinDielectricBsdf::StraightThrough through = tinted.straight_through(float(cos_i));
    for (int lane = 0; lane < 4; ++lane) {
      CAPTURE(lane);
      const double tau = std::pow(double(tau_n[lane]), 1.0 / cos_t);
      const SP rt = sheet_reflectance_transmittance(cos_i, 1.5, tau);
      const double r = rt.s, t = rt.p;
      CHECK(tinted.reflectance(float(cos_i))[lane] == doctest::Approx(r).epsilon(1e-5));
      CHECK(through.transmittance[lane] == doctest::Approx(t).epsilon(1e-5));
      CHECK(through.probability[lane] == doctest::Approx(t / (r + t)).epsilon(1e-5));
    }
    // τₙ = 1 in lane 3: the tinted sheet's lane equals the clear sheet's.
    CHECK(through.transmittance[3] == doctest::Approx(clear.straight_through(float(cos_i)).transmittance[3]).epsilon(1e-6));
    CHECK(clear.straight_through(float(cos_i)).probability[0] == clear.straight_through(float(cos_i)).transmittance[0]);
    // Sampling picks the straight-through lobe with the reported probability, and its sample says the same.
    constexpr int kCount = 100000;
    int passed = 0;
    const Vec3 wo = direction(c);
    for (int i = 0; i < kCount; ++i) {
      const auto s = tinted.sample(wo, u(rng), {0.5f, 0.5f});
      REQUIRE(s);
      if (s->wi.z * wo.z < 0.0f && passed++ == 0) {
        CHECK(s->pdf[1] == doctest::Approx(through.probability[1]).epsilon(1e-6));
        CHECK(s->f[0] * float(cos_i) == doctest::Approx(through.transmittance[0]).epsilon(1e-6));
      }
    }
    const double p = through.probability[0];
    CHECK(std::fabs(double(passed) / kCount - p) < 4.0 * std::sqrt(p * (1 - p) / kCount) + 1e-9);
  }
}
