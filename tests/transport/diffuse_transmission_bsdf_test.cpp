// The Lambertian reflector-transmitter: albedo R + T exactly, the split between the sides, sample/pdf agreement
// by chi-square, and the material's defaults and energy bound.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "bsdf_chi_square.h"
#include "spectral/error.h"
#include "statistics.h"
#include "test_support.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/bsdfs/material.h"

using namespace rimu;

namespace {

Vec3 direction(float cos_theta) {
  const float s = std::sqrt(std::fmax(0.0f, 1.0f - cos_theta * cos_theta));
  return {s * std::cos(0.7f), s * std::sin(0.7f), cos_theta};
}

SpectralTexturePtr constant_texture(double value) {
  return std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(value));
}

}  // namespace

TEST_CASE("diffuse transmission: every sample weighs R + T, and the sides split R : T") {
  const Float4 r(0.25f, 0.6f, 0.0f, 0.1f), t(0.25f, 0.3f, 0.5f, 0.0f);
  const Bsdf bsdf = DiffuseTransmissionBsdf(r, t);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float c : {0.9f, 0.2f, -0.5f}) {
    CAPTURE(c);
    const Vec3 wo = direction(c);
    constexpr int kCount = 100000;
    int transmitted = 0;
    for (int i = 0; i < kCount; ++i) {
      const auto s = bsdf.sample(wo, u(rng), {u(rng), u(rng)});
      REQUIRE(s);
      // f·|cos|/pdf = (R/π)|cos| / (P|cos|/π) = R/P = R + T, the same for both lobes: the albedo, exactly.
      CHECK(s->hero_weight()[0] == doctest::Approx(0.5).epsilon(1e-5));
      // eval and pdf reproduce the sample in every lane.
      const Float4 f = bsdf.eval(wo, s->wi), pdf = bsdf.pdf(wo, s->wi);
      for (int lane = 0; lane < 4; ++lane) {
        CHECK(f[lane] == doctest::Approx(s->f[lane]));
        CHECK(pdf[lane] == doctest::Approx(s->pdf[lane]));
      }
      transmitted += s->wi.z * wo.z < 0.0f;
    }
    // Binomial, 4σ: P(transmit) = T/(R + T) = 0.5 for the hero.
    CHECK(std::fabs(double(transmitted) / kCount - 0.5) < 4.0 * std::sqrt(0.25 / kCount));
  }
  // Lane 2 reflects nothing: its pdf on wo's side is 0; lane 3 transmits nothing.
  const Vec3 wo = direction(0.6f), up = direction(0.8f), down = direction(-0.8f);
  CHECK(bsdf.pdf(wo, up)[2] == 0.0f);
  CHECK(bsdf.pdf(wo, down)[2] == doctest::Approx(0.8 / M_PI));
  CHECK(bsdf.pdf(wo, down)[3] == 0.0f);
  CHECK(bsdf.eval(wo, down)[1] == doctest::Approx(0.3 / M_PI));
  // Nothing to scatter in the hero lane: no sample.
  CHECK_FALSE(DiffuseTransmissionBsdf(Float4(0.0f), Float4(0.0f)).sample(wo, 0.5f, {0.3f, 0.3f}));
}

TEST_CASE("chi-square: diffuse transmission samples the density it reports, from both sides") {
  const double threshold = test::sidak_threshold(0.01, 12);
  uint64_t seed = 21;
  for (const auto& [r, t] : {std::pair{0.25f, 0.25f}, {0.7f, 0.1f}, {0.05f, 0.9f}}) {
    for (float c : {0.9f, 0.3f, -0.5f, -0.05f}) {
      CAPTURE(r);
      CAPTURE(c);
      const auto outcome = test::bsdf_chi_square(DiffuseTransmissionBsdf(Float4(r), Float4(t)), direction(c), 50000, seed++);
      CAPTURE(outcome.failure);
      CAPTURE(outcome.chi_square);
      CHECK(outcome.failure.empty());
      CHECK(outcome.p_value > threshold);
    }
  }
}

TEST_CASE("diffuse transmission material: scale multiplies both, and R + T above 1 is scaled down to 1") {
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f));
  const Material plain = DiffuseTransmissionMaterial(constant_texture(0.25), constant_texture(0.25), 1.0f);
  const Bsdf a = plain.bsdf({}, lambda);
  const auto& da = std::get<DiffuseTransmissionBsdf>(a.variant());
  CHECK(da.reflectance()[0] == doctest::Approx(0.25));
  CHECK(da.transmittance()[3] == doctest::Approx(0.25));
  // scale 3: R = T = 0.75 would scatter 1.5 of the incident flux; normalised to R + T = 1, keeping R : T.
  const Material bright = DiffuseTransmissionMaterial(constant_texture(0.25), constant_texture(0.25), 3.0f);
  const Bsdf b = bright.bsdf({}, lambda);
  const auto& db = std::get<DiffuseTransmissionBsdf>(b.variant());
  CHECK(db.reflectance()[1] == doctest::Approx(0.5));
  CHECK(db.transmittance()[1] == doctest::Approx(0.5));
  CHECK_THROWS_AS(DiffuseTransmissionMaterial(nullptr, constant_texture(0.25), 1.0f), InputError);
  CHECK_THROWS_AS(DiffuseTransmissionMaterial(constant_texture(0.25), constant_texture(0.25), -1.0f), InputError);
}
