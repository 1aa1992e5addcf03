// Energy conservation of every BSDF, estimated from its own sample weights, and the weights' consistency with
// eval()/pdf().
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "bsdf_test_fixtures.h"
#include "spectral/library/optical_constants.h"
#include "test_support.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/bsdfs/fresnel.h"

using namespace rimu;

namespace bsdf_energy_test {

Vec3 direction(float cos_theta) {
  const float s = std::sqrt(std::fmax(0.0f, 1.0f - cos_theta * cos_theta));
  return {s * std::cos(0.3f), s * std::sin(0.3f), cos_theta};
}

struct Albedo {
  double mean = 0, standard_error = 0;
};

/// The directional albedo ∫ f |cos θi| dωi of the hero lane, as the mean of the sample weights f·|cos|/pdf (0 for
/// failed samples). `flux` undoes the radiance scaling 1/η'² of refraction, so the result is the fraction of
/// flux scattered (what energy conservation bounds by 1).
Albedo albedo(const Bsdf& bsdf, Vec3 wo, int count, float eta_hero_inside = 1.0f) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < count; ++i) {
    const float ul = u(rng), u1 = u(rng), u2 = u(rng);
    const auto s = bsdf.sample(wo, ul, {u1, u2});
    if (!s) continue;
    double w = s->hero_weight()[0];
    if (s->wi.z * wo.z < 0.0f) {
      const double eta_ratio = wo.z > 0.0f ? eta_hero_inside : 1.0 / eta_hero_inside;  // η' = n_i/n_o
      w *= eta_ratio * eta_ratio;
    }
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / count;
  return {mean, std::sqrt(std::fmax(0.0, sum2 / count - mean * mean) / count)};
}

constexpr int kCount = 100000;
constexpr double kSigmas = 4.0;  // a 4σ bound: false alarms ~6e-5 per check

TEST_CASE("energy: a white Lambertian reflects exactly everything, sample by sample") {
  // f·cos/pdf = (1/π)·cos/(cos/π) = 1 for every sample: exact up to float rounding.
  const Bsdf white = DiffuseBsdf(Float4(1.0f));
  for (float c : {1.0f, 0.5f, 0.01f, -0.3f}) {
    const Albedo a = albedo(white, direction(c), 20000);
    CHECK(a.mean == doctest::Approx(1.0).epsilon(1e-5));
  }
}

TEST_CASE("energy: a smooth mirror reflects F exactly, and a conductor with F = 1 loses only masked energy") {
  // k = 1e4, n = 1: normal-incidence reflectance 1 − 4/(4 + k²) = 1 − 4e-8: a perfect mirror in float.
  const Float4 n(1.0f), k(1e4f);
  const Bsdf mirror = ConductorBsdf(n, k, TrowbridgeReitz(0.0f, 0.0f));
  for (float c : {1.0f, 0.5f, 0.01f}) {
    const auto s = mirror.sample(direction(c), 0.5f, {0.5f, 0.5f});
    REQUIRE(s);
    CHECK(s->is_delta);
    CHECK(s->wi.z == doctest::Approx(c));
    // The weight of a delta mirror is F(θo) itself; with k² = 1e8 the complex float arithmetic rounds F to within
    // a few 1e-6 of 1 (the exact value differs from 1 by < 4e-8).
    CHECK(s->hero_weight()[0] == doctest::Approx(fresnel_conductor(Float4(c), n, k)[0]).epsilon(1e-7));
    CHECK(s->hero_weight()[0] == doctest::Approx(1.0).epsilon(1e-5));
  }
  // Rough: single-scattering GGX loses the light that would bounce twice between facets, so the albedo is ≤ 1;
  // at α = 0.05 and near-normal incidence the loss is far below 1% (Kulla & Conty 2017 show the multiple-scattering
  // energy vanishing as α → 0), so ≥ 0.99 is the physical bound used.
  for (float alpha : {0.05f, 0.3f, 0.8f}) {
    for (float c : {0.9f, 0.5f, 0.05f}) {
      CAPTURE(alpha);
      CAPTURE(c);
      const Albedo a = albedo(ConductorBsdf(n, k, TrowbridgeReitz(alpha, alpha)), direction(c), kCount);
      CAPTURE(a.mean);
      CHECK(a.mean <= 1.0 + kSigmas * a.standard_error);
      if (alpha == 0.05f && c >= 0.5f) CHECK(a.mean >= 0.99 - kSigmas * a.standard_error);
    }
  }
}

TEST_CASE("energy: rough BK7 scatters at most all flux by reflection plus transmission, nearly all when smooth") {
  const SampledWavelengths lambda(Float4(550.0f, 650.0f, 450.0f, 750.0f), Float4(1.0f));
  const Float4 eta = test::bk7_eta(lambda);
  // Smooth: R + T = 1 exactly (flux), both sides, including total internal reflection.
  for (float c : {0.9f, 0.3f, -0.9f, -0.3f}) {
    const Albedo a = albedo(DielectricBsdf(eta, TrowbridgeReitz(0, 0)), direction(c), 20000, eta[0]);
    CHECK(a.mean == doctest::Approx(1.0).epsilon(1e-5));
  }
  for (float alpha : {0.05f, 0.3f, 0.8f}) {
    for (float c : {0.9f, 0.5f, 0.05f, -0.9f, -0.5f}) {
      CAPTURE(alpha);
      CAPTURE(c);
      const Albedo a = albedo(DielectricBsdf(eta, TrowbridgeReitz(alpha, alpha)), direction(c), kCount, eta[0]);
      CAPTURE(a.mean);
      CHECK(a.mean <= 1.0 + kSigmas * a.standard_error);
      if (alpha == 0.05f && std::fabs(c) >= 0.5f) CHECK(a.mean >= 0.99 - kSigmas * a.standard_error);
    }
  }
}

TEST_CASE("energy: coated diffuse with a white base conserves energy exactly, and absorbs with a grey one") {
  // ρ = 1: F(θo) + (1 − F(θo)) = 1 for every wo (coated_diffuse_bsdf.h); the estimate's noise comes from the lobe
  // choice only. ρ = 0.5: the albedo is F + (1−F)·(1 − F̄_ext)·ρ/(η²(1 − ρF̄_int))... < 1.
  const Float4 eta(1.5f);
  const Float4 diffuse_fresnel(float(fresnel_diffuse_reflectance(1.5)));
  for (float c : {1.0f, 0.5f, 0.05f, -0.5f}) {
    CAPTURE(c);
    const Albedo white = albedo(CoatedDiffuseBsdf(Float4(1.0f), eta, diffuse_fresnel), direction(c), kCount);
    CHECK(std::abs(white.mean - 1.0) <= kSigmas * white.standard_error + 1e-5);
    const Albedo grey = albedo(CoatedDiffuseBsdf(Float4(0.5f), eta, diffuse_fresnel), direction(c), kCount);
    CHECK(grey.mean < 0.9);
  }
}

TEST_CASE("sample weights: f and pdf of non-delta samples are what eval() and pdf() return, in every lane") {
  const SampledWavelengths lambda = test::four_visible_wavelengths();
  const auto bsdfs = test::one_bsdf_of_each_kind("gold", lambda, test::bk7_eta(lambda));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const Bsdf& bsdf : bsdfs) {
    for (float c : {0.8f, 0.2f, -0.6f}) {
      for (int i = 0; i < 200; ++i) {
        const Vec3 wo = direction(c);
        const auto s = bsdf.sample(wo, u(rng), {u(rng), u(rng)});
        if (!s || s->is_delta) continue;
        const Float4 f = bsdf.eval(wo, s->wi), pdf = bsdf.pdf(wo, s->wi);
        for (int lane = 0; lane < 4; ++lane) {
          // Recomputing the half vector from wo + wi rounds differently from the sampled one: 1e-3 relative.
          CHECK(s->f[lane] == doctest::Approx(f[lane]).epsilon(1e-3));
          CHECK(s->pdf[lane] == doctest::Approx(pdf[lane]).epsilon(1e-3));
        }
      }
    }
  }
}

TEST_CASE("spectral MIS: lane k's pdf is the pdf of the same BSDF with lane k as the hero") {
  // Rotating the lanes so that λ_k leads must move lane k's value to lane 0, for eval() and pdf().
  const SpectrumPtr sf11 = dielectric_ior(test::library(), "sf11");  // strongly dispersive
  const Float4 lambda_nm(450.0f, 550.0f, 650.0f, 750.0f);
  const auto rotated = [&](int k) {
    return SampledWavelengths(Float4(lambda_nm[k], lambda_nm[(k + 1) % 4], lambda_nm[(k + 2) % 4], lambda_nm[(k + 3) % 4]),
                              Float4(1.0f));
  };
  const Vec3 wo = direction(0.6f), wi_reflect{-0.3f, 0.2f, 0.93f}, wi_transmit{-0.5f, -0.1f, -0.86f};
  for (float alpha : {0.05f, 0.3f}) {
    const DielectricBsdf base(sf11->sample(rotated(0)), TrowbridgeReitz(alpha, alpha));
    for (int k = 1; k < 4; ++k) {
      const DielectricBsdf hero_k(sf11->sample(rotated(k)), TrowbridgeReitz(alpha, alpha));
      for (Vec3 wi : {normalize(wi_reflect), normalize(wi_transmit)}) {
        CHECK(base.pdf(wo, wi)[k] == doctest::Approx(hero_k.pdf(wo, wi)[0]).epsilon(1e-6));
        if (alpha == 0.3f) CHECK(base.pdf(wo, wi)[k] > 0.0f);  // not vacuously 0 = 0
        CHECK(base.eval(wo, wi)[k] == doctest::Approx(hero_k.eval(wo, wi)[0]).epsilon(1e-6));
      }
    }
  }
}

TEST_CASE("robustness: grazing and degenerate directions never give NaN or Inf") {
  const Float4 eta = test::bk7_eta(test::four_visible_wavelengths());
  const Bsdf bsdfs[] = {
      DiffuseBsdf(Float4(0.5f)),
      ConductorBsdf(Float4(0.2f), Float4(3.0f), TrowbridgeReitz(0.0f, 0.0f)),
      ConductorBsdf(Float4(0.2f), Float4(3.0f), TrowbridgeReitz(0.05f, 0.05f)),
      ConductorBsdf(Float4(1.0f), Float4(0.0f), TrowbridgeReitz(0.3f, 0.3f)),  // n = 1, k = 0: reflects nothing
      DielectricBsdf(eta, TrowbridgeReitz(0.0f, 0.0f)),
      DielectricBsdf(eta, TrowbridgeReitz(0.05f, 0.05f)),
      DielectricBsdf(eta, TrowbridgeReitz(0.8f, 0.8f)),
      DielectricBsdf(Float4(1.0f), TrowbridgeReitz(0.3f, 0.3f)),  // index-matched: no interface
      CoatedDiffuseBsdf(Float4(0.5f), eta, Float4(0.09f)),
  };
  const Vec3 directions[] = {{0, 0, 1},     {1, 0, 0},      {0.6f, 0.8f, 0.0f}, {1, 0, 1e-8f},  {1, 0, -1e-8f},
                             {0, 0, -1},    {-1, 0, 0},     {0.0f, 1.0f, -0.0f}, direction(0.01f), direction(-0.01f)};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const Bsdf& bsdf : bsdfs) {
    for (Vec3 wo : directions) {
      wo = normalize(wo);
      for (Vec3 wi : directions) {
        wi = normalize(wi);
        CHECK(is_finite(bsdf.eval(wo, wi)).all());
        CHECK(is_finite(bsdf.pdf(wo, wi)).all());
      }
      for (int i = 0; i < 200; ++i) {
        const auto s = bsdf.sample(wo, u(rng), {u(rng), u(rng)});
        if (!s) continue;
        CHECK(s->pdf[0] > 0.0f);
        CHECK(is_finite(s->wi));
        CHECK(is_finite(s->f).all());
        CHECK(is_finite(s->pdf).all());
        CHECK(is_finite(s->hero_weight()).all());
      }
    }
  }
}

TEST_CASE("diffuse entry: from inside, the way out holds (1 − F(wo)) η² of the radiance, as the flux balance needs") {
  // ∫ f cos θi dωi over the outside = (1 − F(wo)) (1 − F̄_ext) / (1 − F̄_int) = (1 − F(wo)) η² (reciprocity of the
  // hemispherical Fresnel averages): the lobe carries radiance η² times denser out, as a refraction out would, so
  // flux is conserved (the white furnace in media_slab_reference_test.cpp closes the loop). Quadrature of eval()
  // in μ = cos θi (the lobe is isotropic in φ), and the mean sample weight of the non-delta samples.
  for (float eta : {1.33f, 1.5f, 2.4f}) {
    const Float4 norm(float(DielectricBsdf::diffuse_entry_normalisation(eta)));
    const DielectricBsdf boundary(Float4(eta), TrowbridgeReitz(0, 0), norm);
    for (float c : {0.95f, 0.7f, 0.3f}) {
      CAPTURE(eta);
      CAPTURE(c);
      const Vec3 wo = direction(-c);
      const double leave = 1.0 - fresnel_dielectric(double(-c), double(eta));
      constexpr int n = 20000;
      double integral = 0.0;
      for (int i = 0; i < n; ++i) {
        const float mu = (i + 0.5f) / n;
        const Vec3 wi{std::sqrt(1.0f - mu * mu), 0.0f, mu};
        integral += boundary.eval(wo, wi)[0] * mu * 2.0 * std::numbers::pi / n;
      }
      if (c < std::sqrt(1.0f - 1.0f / (eta * eta))) CHECK(leave == 0.0);  // beyond the critical angle: no way out
      CHECK(integral == doctest::Approx(leave * eta * eta).epsilon(1e-4));
      // Sampled: the delta share is R(wo), the rest weighs f cos/pdf with f and pdf what eval() and pdf() give.
      std::mt19937_64 rng(11);
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      double sum = 0.0, sum2 = 0.0;
      int mirrored = 0;
      for (int i = 0; i < kCount; ++i) {
        const auto s = boundary.sample(wo, u(rng), {u(rng), u(rng)});
        REQUIRE(s);
        if (s->is_delta) {
          ++mirrored;
          CHECK(s->wi.z == doctest::Approx(-c));
          continue;
        }
        CHECK(s->wi.z > 0.0f);
        CHECK(s->eta == doctest::Approx(1.0f / eta));
        CHECK(s->f[0] == doctest::Approx(boundary.eval(wo, s->wi)[0]).epsilon(1e-6));
        CHECK(s->pdf[0] == doctest::Approx(boundary.pdf(wo, s->wi)[0]).epsilon(1e-6));
        const double w = s->hero_weight()[0];
        sum += w;
        sum2 += w * w;
      }
      // Binomial: the mirror's share within 5 standard errors of R; the weights' mean estimates the integral.
      const double r = 1.0 - leave;
      CHECK(std::fabs(mirrored / double(kCount) - r) <= 5.0 * std::sqrt(r * (1 - r) / kCount) + 1e-9);
      const double mean = sum / kCount, se = std::sqrt(std::fmax(0.0, sum2 / kCount - mean * mean) / kCount);
      CHECK(std::fabs(mean - leave * eta * eta) <= 5.0 * se + 1e-6);
    }
  }
  // From outside the boundary is the plain dielectric: smooth, nothing to evaluate.
  const DielectricBsdf boundary(Float4(1.5f), TrowbridgeReitz(0, 0), Float4(1.0f));
  CHECK(boundary.eval(direction(0.5f), direction(-0.5f))[0] == 0.0f);
  CHECK(boundary.eval(direction(0.5f), direction(0.5f))[0] == 0.0f);
  CHECK(boundary.flags().has_non_delta);
}

}  // namespace bsdf_energy_test
