// Helmholtz reciprocity of the BSDFs, and the generalised reciprocity of refraction for radiance.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "bsdf_test_fixtures.h"
#include "transport/bsdfs/bsdf.h"

using namespace rimu;

namespace {

Vec3 random_direction(std::mt19937_64& rng, bool upper) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float z = 0.02f + 0.97f * u(rng), phi = 6.2831853f * u(rng), s = std::sqrt(1.0f - z * z);
  return {s * std::cos(phi), s * std::sin(phi), upper ? z : -z};
}

}  // namespace

TEST_CASE("reciprocity: reflection is symmetric, f(wo, wi) = f(wi, wo), for every reflecting BSDF") {
  // Float rounding in D, G and Fresnel (a few tens of operations): 1e-4 relative.
  const SampledWavelengths lambda = test::four_visible_wavelengths();
  const auto bsdfs = test::one_bsdf_of_each_kind("copper", lambda, test::bk7_eta(lambda));
  std::mt19937_64 rng(5);
  for (const Bsdf& bsdf : bsdfs) {
    for (int i = 0; i < 200; ++i) {
      const bool upper = i % 2 == 0;  // the dielectric also reflects internally
      const Vec3 a = random_direction(rng, upper), b = random_direction(rng, upper);
      const Float4 forward = bsdf.eval(a, b), backward = bsdf.eval(b, a);
      for (int lane = 0; lane < 4; ++lane) CHECK(forward[lane] == doctest::Approx(backward[lane]).epsilon(1e-4));
    }
  }
}

TEST_CASE("reciprocity: rough refraction satisfies f(wo, wi)/n_o^2 = f(wi, wo)/n_i^2 for radiance") {
  // Veach 1997, Eq. 5.14: the radiance BTDF is not symmetric; f/n² of the side the first argument is on is.
  const Float4 eta = test::bk7_eta(test::four_visible_wavelengths());
  std::mt19937_64 rng(9);
  for (float alpha : {0.05f, 0.3f, 0.8f}) {
    const DielectricBsdf glass(eta, TrowbridgeReitz(alpha, alpha));
    int nonzero = 0;
    for (int i = 0; i < 300; ++i) {
      const Vec3 outside = random_direction(rng, true), inside = random_direction(rng, false);
      const Float4 out_in = glass.eval(outside, inside), in_out = glass.eval(inside, outside);
      for (int lane = 0; lane < 4; ++lane) {
        const float n_inside = eta[lane];
        CHECK(out_in[lane] / 1.0f == doctest::Approx(in_out[lane] / (n_inside * n_inside)).epsilon(1e-4));
        nonzero += out_in[lane] > 0.0f;
      }
    }
    CHECK(nonzero > 100);  // the check above must not pass vacuously on zeros
  }
}

TEST_CASE("radiance scaling: a sampled refraction reports η' = n(wi's side)/n(wo's side), the factor 1/η'² in its f") {
  // Russian roulette divides the radiance scaling out of the throughput with BsdfSample::eta, so it must be the
  // factor f carries: for a rough refraction f(wo, wi)·η'² = f(wi, wo) (the reciprocity above), and for a smooth
  // one f·|cos θi|/pdf = 1/η'² in the hero lane (pdf = T, f = T/(|cos θi| η'²)). Reflections report 1.
  const Float4 eta = test::bk7_eta(test::four_visible_wavelengths());
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const Float4 hero_eta(eta[0]);  // one η: no dispersion
  for (float alpha : {0.0f, 0.1f, 0.5f}) {
    const DielectricBsdf glass(hero_eta, TrowbridgeReitz(alpha, alpha));
    int refractions = 0, reflections = 0;
    for (int i = 0; i < 400; ++i) {
      const Vec3 wo = random_direction(rng, i % 2 == 0);
      const auto s = glass.sample(wo, u(rng), Vec2{u(rng), u(rng)});
      if (!s) continue;
      if (s->wi.z * wo.z > 0.0f) {
        CHECK(s->eta == 1.0f);
        ++reflections;
        continue;
      }
      ++refractions;
      const float expected = wo.z > 0.0f ? eta[0] : 1.0f / eta[0];
      CHECK(s->eta == doctest::Approx(expected).epsilon(1e-6));
      if (alpha == 0.0f) {
        CHECK(s->hero_weight()[0] * s->eta * s->eta == doctest::Approx(1.0f).epsilon(1e-4));
      } else {
        CHECK(glass.eval(wo, s->wi)[0] * s->eta * s->eta == doctest::Approx(glass.eval(s->wi, wo)[0]).epsilon(1e-4));
      }
    }
    CHECK(refractions > 100);  // both kinds happen, so neither check passes vacuously
    CHECK(reflections > 5);
  }
}

TEST_CASE("rough dielectric: eval_with_reverse_pdf gives eval(wo, wi) and pdf(wi, wo), both ways and per lane") {
  // The layered walk takes f and the other side's density from one evaluation; each must be what the separate
  // calls give. Both share the half vector, D and G; the reverse density's Fresnel factor is taken from wo's side,
  // equal to wi's by Snell's law at the half vector, so they agree to float rounding (1e-4 relative).
  std::mt19937_64 rng(21);
  const Float4 dispersive = test::bk7_eta(test::four_visible_wavelengths());
  for (const Float4 eta : {Float4(1.5f), dispersive}) {
    for (float alpha : {0.05f, 0.3f, 0.8f}) {
      const DielectricBsdf glass(eta, TrowbridgeReitz(alpha, alpha));
      int nonzero = 0;
      for (int i = 0; i < 400; ++i) {
        const Vec3 wo = random_direction(rng, i % 2 == 0), wi = random_direction(rng, i % 4 < 2);
        Float4 reverse;
        const Float4 f = glass.eval_with_reverse_pdf(wo, wi, reverse);
        const Float4 f_alone = glass.eval(wo, wi), reverse_alone = glass.pdf(wi, wo);
        for (int lane = 0; lane < 4; ++lane) {
          CHECK(f[lane] == f_alone[lane]);
          CHECK(reverse[lane] == doctest::Approx(reverse_alone[lane]).epsilon(1e-4));
          nonzero += reverse[lane] > 0.0f;
        }
      }
      CHECK(nonzero > 400);  // reflection and refraction both reached, not zeros compared
    }
  }
}
