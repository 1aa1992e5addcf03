// Materials turn spectral inputs into BSDFs at the path's wavelengths.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <variant>

#include "spectral/error.h"
#include "spectral/library/optical_constants.h"
#include "test_support.h"
#include "transport/bsdfs/material.h"

using namespace rimu;

namespace {

SpectralTexturePtr constant_texture(double value) {
  return std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(value));
}

using rimu::test::kLambda;

}  // namespace

TEST_CASE("material: diffuse evaluates its reflectance per lane and clamps it to [0, 1]") {
  auto& lib = test::library();
  const Material patch = DiffuseMaterial(std::make_shared<ConstantSpectralTexture>(lib.colorchecker_patch("dark_skin")));
  const Bsdf bsdf = patch.bsdf(MaterialContext::at_uv({0.5f, 0.5f}), kLambda);
  REQUIRE(std::holds_alternative<DiffuseBsdf>(bsdf.variant()));
  const Float4 albedo = std::get<DiffuseBsdf>(bsdf.variant()).albedo();
  const Float4 expected = lib.colorchecker_patch("dark_skin")->sample(kLambda);
  for (int lane = 0; lane < 4; ++lane) CHECK(albedo[lane] == expected[lane]);
  const Material too_bright = DiffuseMaterial(constant_texture(1.5));
  CHECK(std::get<DiffuseBsdf>(too_bright.bsdf({}, kLambda).variant()).albedo()[0] == 1.0f);
  CHECK(!bsdf.flags().has_delta);
  CHECK(!bsdf.flags().has_transmission);
}

TEST_CASE("material: conductors and dielectrics are smooth at roughness 0 and rough above it") {
  auto& lib = test::library();
  const Material mirror = ConductorMaterial(conductor_ior(lib, "silver"), 0.0f);
  const Material brushed = ConductorMaterial(conductor_ior(lib, "aluminium"), 0.2f, 0.6f);
  CHECK(mirror.bsdf({}, kLambda).flags().has_delta);
  CHECK(!brushed.bsdf({}, kLambda).flags().has_delta);
  CHECK(brushed.bsdf({}, kLambda).flags().has_non_delta);
  const Material glass = DielectricMaterial(dielectric_ior(lib, "bk7"), 0.0f);
  const Material frosted = DielectricMaterial(dielectric_ior(lib, "water"), 0.5f);
  CHECK(glass.bsdf({}, kLambda).flags().has_transmission);
  CHECK(glass.bsdf({}, kLambda).flags().has_delta);
  CHECK(frosted.bsdf({}, kLambda).flags().has_non_delta);
}

TEST_CASE("material: a Sellmeier glass disperses, a constant index does not") {
  const Vec3 wo = normalize(Vec3(0.6f, 0.0f, 0.8f));
  const Material bk7 = DielectricMaterial(dielectric_ior(test::library(), "bk7"), 0.0f);
  const Material constant = DielectricMaterial(std::make_shared<ConstantSpectrum>(1.5), 0.0f);
  const auto dispersed = bk7.bsdf({}, kLambda).sample(wo, 0.99f, {0.5f, 0.5f});
  const auto plain = constant.bsdf({}, kLambda).sample(wo, 0.99f, {0.5f, 0.5f});
  REQUIRE(dispersed);
  REQUIRE(plain);
  CHECK(dispersed->wavelength_dependent_direction);
  CHECK(!plain->wavelength_dependent_direction);
  CHECK(plain->pdf[3] == doctest::Approx(plain->pdf[0]));  // every lane could have refracted here
}

TEST_CASE("material: coated diffuse under a glass coat conserves energy with a white base") {
  // The coat's F̄_ext is tabulated over wavelength; a white base must still give albedo 1 (coated_diffuse_bsdf.h).
  const Material coated = CoatedDiffuseMaterial(constant_texture(1.0), dielectric_ior(test::library(), "bk7"));
  const Bsdf bsdf = coated.bsdf({}, kLambda);
  const Vec3 wo = normalize(Vec3(0.3f, 0.1f, 0.9f));
  // Albedo = F(θo) + ∫ f_diffuse cos dωi, the integral by a 200×200 midpoint rule in (cos θ, φ) (error ~1e-5).
  Float4 integral(0.0f);
  const int steps = 200;
  for (int i = 0; i < steps; ++i) {
    const float z = (i + 0.5f) / steps, s = std::sqrt(1.0f - z * z);
    for (int j = 0; j < steps; ++j) {
      const float phi = 6.2831853f * (j + 0.5f) / steps;
      integral += bsdf.eval(wo, {s * std::cos(phi), s * std::sin(phi), z}) * Float4(z);
    }
  }
  integral *= Float4(6.2831853f / (steps * steps));
  const auto specular = bsdf.sample(wo, 0.0f, {0.5f, 0.5f});
  REQUIRE(specular);
  REQUIRE(specular->is_delta);
  const Float4 total = integral + specular->f * Float4(specular->wi.z);
  for (int lane = 0; lane < 4; ++lane) CHECK(total[lane] == doctest::Approx(1.0).epsilon(2e-4));
}

TEST_CASE("material: invalid parameters are input errors") {
  auto& lib = test::library();
  CHECK_THROWS_AS(ConductorMaterial(conductor_ior(lib, "gold"), 1.5f), InputError);
  CHECK_THROWS_AS(DielectricMaterial(dielectric_ior(lib, "bk7"), -0.1f), InputError);
  CHECK_THROWS_AS(DielectricMaterial(std::make_shared<ConstantSpectrum>(0.0), 0.0f), InputError);
  CHECK_THROWS_AS(CoatedDiffuseMaterial(constant_texture(0.5), std::make_shared<ConstantSpectrum>(0.8)), InputError);
  CHECK_THROWS_AS(DiffuseMaterial(nullptr), InputError);
}

namespace {

CoatLayer layer(float roughness, float thickness = 0.0f, SpectralTexturePtr albedo = nullptr) {
  CoatLayer l;
  l.roughness = roughness;
  l.thickness = thickness;
  l.albedo = std::move(albedo);
  return l;
}

// A context at a point of the unit square (z = 0) seen from straight above: what MixMaterial hashes.
MaterialContext context_at(float x, float y) {
  MaterialContext c;
  c.position = {x, y, 0.0f};
  c.geometric_normal = c.shading_normal = {0.0f, 0.0f, 1.0f};
  c.wo = {0.0f, 0.0f, 1.0f};
  return c;
}

bool chose_second(const MixMaterial& mix, const MaterialContext& c) {
  return std::holds_alternative<DielectricMaterial>(mix.choose(c).variant());
}

}  // namespace

TEST_CASE("material: coated materials choose the closed form or the random walk by the stated rule") {
  const auto ior = std::make_shared<ConstantSpectrum>(1.5);
  const auto kind = [&](const Material& m) { return m.bsdf(MaterialContext::at_uv({0.5f, 0.5f}), kLambda).variant().index(); };
  const size_t closed = Bsdf::Variant(CoatedDiffuseBsdf(Float4(0.5f), Float4(1.5f), Float4(0.09f))).index();
  const size_t walk = Bsdf::Variant(LayeredBsdf(1.5f, TrowbridgeReitz(0, 0), DiffuseBsdf(Float4(0.5f)), {}, {})).index();
  // Smooth and not scattering (no albedo, or zero thickness): the exact closed form, absorbing if thick.
  CHECK(kind(CoatedDiffuseMaterial(constant_texture(0.5), ior)) == closed);
  CHECK(kind(CoatedDiffuseMaterial(constant_texture(0.5), ior, layer(0.0f, 0.01f))) == closed);
  CHECK(kind(CoatedDiffuseMaterial(constant_texture(0.5), ior, layer(0.0f, 0.0f, constant_texture(0.5)))) == closed);
  // Rough, or a scattering slab: the walk.
  CHECK(kind(CoatedDiffuseMaterial(constant_texture(0.5), ior, layer(0.3f, 0.0f))) == walk);
  CHECK(kind(CoatedDiffuseMaterial(constant_texture(0.5), ior, layer(0.0f, 0.1f, constant_texture(0.5)))) == walk);
  // A coated conductor is always the walk.
  CHECK(kind(CoatedConductorMaterial(ior, conductor_ior(test::library(), "gold"), 0.0f, 0.0f, {})) == walk);
  // The absorbing closed form darkens the clear one: thickness 0.5 at normal incidence loses ≥ exp(−1) of the
  // diffuse lobe (two crossings), more with the internal loop.
  const Vec3 up{0, 0, 1};
  const Float4 clear = CoatedDiffuseMaterial(constant_texture(0.8), ior).bsdf({}, kLambda).eval(up, up);
  const Float4 thick = CoatedDiffuseMaterial(constant_texture(0.8), ior, layer(0.0f, 0.5f)).bsdf({}, kLambda).eval(up, up);
  CHECK(thick[0] < clear[0] * std::exp(-1.0f) * 1.0001f);
  CHECK(thick[0] > 0.0f);
}

TEST_CASE("material: invalid coat layers are input errors") {
  const auto ior = std::make_shared<ConstantSpectrum>(1.5);
  CHECK_THROWS_AS(CoatedDiffuseMaterial(constant_texture(0.5), ior, layer(1.5f)), InputError);
  CHECK_THROWS_AS(CoatedDiffuseMaterial(constant_texture(0.5), ior, layer(0.0f, -1.0f)), InputError);
  CoatLayer bad_g;
  bad_g.g = 1.0f;
  CHECK_THROWS_AS(CoatedDiffuseMaterial(constant_texture(0.5), ior, bad_g), InputError);
  CoatLayer no_walk;
  no_walk.walk.samples = 0;
  CHECK_THROWS_AS(CoatedConductorMaterial(ior, conductor_ior(test::library(), "gold"), 0.0f, 0.0f, no_walk), InputError);
  CHECK_THROWS_AS(CoatedConductorMaterial(ior, ComplexIorSpectra{}, 0.0f, 0.0f, {}), InputError);
  CHECK_THROWS_AS(CoatedConductorMaterial(std::make_shared<ConstantSpectrum>(0.9), conductor_ior(test::library(), "gold"), 0.0f, 0.0f, {}),
                  InputError);
}

TEST_CASE("material context: the hit hash is deterministic and spreads neighbouring points uniformly") {
  const MaterialContext a = context_at(0.25f, 0.5f);
  CHECK(a.hash() == context_at(0.25f, 0.5f).hash());
  CHECK(a.hash() != context_at(std::nextafter(0.25f, 1.0f), 0.5f).hash());
  MaterialContext other_direction = a;
  other_direction.wo = {0.0f, 0.6f, 0.8f};
  CHECK(a.hash() != other_direction.hash());
  // 10 bins over a 316×316 grid of points 1/316 apart: a chi-square test of the hashed values' uniformity
  // (9 degrees of freedom; 27.9 is the 0.999 quantile).
  std::array<int, 10> bins{};
  const int n = 316;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) ++bins[size_t(unit_float_from_hash(context_at(float(i) / n, float(j) / n).hash()) * 10.0f)];
  const double expected = double(n) * n / 10.0;
  double chi2 = 0.0;
  for (int b : bins) chi2 += (b - expected) * (b - expected) / expected;
  CHECK(chi2 < 27.9);
}

TEST_CASE("material: mix chooses per hit, the second with probability amount, the same choice at the same hit") {
  auto first = std::make_shared<const Material>(DiffuseMaterial(constant_texture(0.5)));
  auto second = std::make_shared<const Material>(DielectricMaterial(std::make_shared<ConstantSpectrum>(1.5), 0.0f));
  const auto mix_of = [&](float amount, uint32_t salt = 1) {
    return MixMaterial(first, second, std::make_shared<ConstantFloatTexture>(amount), salt);
  };
  SUBCASE("certain amounts") {
    for (int i = 0; i < 100; ++i) {
      CHECK(!chose_second(mix_of(0.0f), context_at(float(i) / 100.0f, 0.3f)));
      CHECK(chose_second(mix_of(1.0f), context_at(float(i) / 100.0f, 0.3f)));
    }
  }
  SUBCASE("the share of the second over many points is the amount (binomial, 4.5 standard errors)") {
    for (float amount : {0.1f, 0.3f, 0.5f, 0.9f}) {
      const MixMaterial mix = mix_of(amount);
      const int n = 300;
      int second_count = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) second_count += chose_second(mix, context_at(float(i) / n, float(j) / n));
      const double share = double(second_count) / (n * n);
      const double standard_error = std::sqrt(amount * (1.0 - amount) / (n * n));
      CHECK(std::abs(share - amount) <= 4.5 * standard_error);
    }
  }
  SUBCASE("deterministic per hit; different salts choose independently") {
    const MixMaterial a = mix_of(0.5f, 1), b = mix_of(0.5f, 2);
    int agree = 0;
    const int n = 10000;
    for (int i = 0; i < n; ++i) {
      const MaterialContext c = context_at(float(i) / n, 0.7f);
      CHECK(chose_second(a, c) == chose_second(a, c));
      agree += chose_second(a, c) == chose_second(b, c);
    }
    // Independent 50/50 choices agree half the time (binomial standard error 0.005).
    CHECK(std::abs(double(agree) / n - 0.5) <= 4.5 * 0.005);
  }
  SUBCASE("the BSDF is the chosen material's") {
    const MaterialContext c = context_at(0.1f, 0.2f);
    const MixMaterial mix = mix_of(0.5f);
    CHECK(Material(mix).bsdf(c, kLambda).flags().has_transmission == chose_second(mix, c));
  }
  CHECK_THROWS_AS(MixMaterial(first, nullptr, std::make_shared<ConstantFloatTexture>(0.5f), 0), InputError);
}

TEST_CASE("material: a coated conductor by reflectance is the coated conductor of n = 1, k = 2√(r/(1 − r))") {
  // pbrt-v4's artist metal under a coat: r = 0.5 gives k = 2, r = 0.8 gives k = 4. Same walk seed, same BSDF.
  const auto ior = std::make_shared<ConstantSpectrum>(1.5);
  CoatLayer rough;
  rough.roughness = 0.3f;
  for (const auto& [r, k] : {std::pair{0.5, 2.0}, std::pair{0.8, 4.0}}) {
    CAPTURE(r);
    const CoatedConductorMaterial by_reflectance(ior, constant_texture(r), 0.2f, 0.2f, rough);
    const CoatedConductorMaterial by_ior(ior, ComplexIorSpectra{std::make_shared<ConstantSpectrum>(1.0), std::make_shared<ConstantSpectrum>(k)},
                                         0.2f, 0.2f, rough);
    for (const Vec3 wi : {Vec3{0, 0, 1}, normalize(Vec3{0.3f, 0.1f, 0.9f}), normalize(Vec3{-0.6f, 0.2f, 0.5f})}) {
      const Vec3 wo = normalize(Vec3{0.2f, -0.4f, 0.8f});
      const Float4 a = by_reflectance.bsdf({}, kLambda).eval(wo, wi), b = by_ior.bsdf({}, kLambda).eval(wo, wi);
      for (int l = 0; l < 4; ++l) CHECK(a[l] == doctest::Approx(b[l]).epsilon(1e-5));
      CHECK(a[0] > 0.0f);
    }
  }
  CHECK_THROWS_AS(CoatedConductorMaterial(ior, SpectralTexturePtr{}, 0.0f, 0.0f, {}), InputError);
}

namespace {

// A roughness that reads `left` where u < 0.5 and `right` elsewhere.
struct SteppedRoughness final : FloatTexture {
  SteppedRoughness(float left, float right) : left(left), right(right) {}
  float evaluate(const MaterialContext& c) const override { return c.uv.x < 0.5f ? left : right; }
  float left, right;
};

}  // namespace

TEST_CASE("material: a textured coat roughness is the number it reads, per hit, and picks the closed form where it is 0") {
  const auto ior = std::make_shared<ConstantSpectrum>(1.5);
  const auto kind = [&](const Material& m, float u) { return m.bsdf(MaterialContext::at_uv({u, 0.5f}), kLambda).variant().index(); };
  const size_t closed = Bsdf::Variant(CoatedDiffuseBsdf(Float4(0.5f), Float4(1.5f), Float4(0.09f))).index();
  const size_t walk = Bsdf::Variant(LayeredBsdf(1.5f, TrowbridgeReitz(0, 0), DiffuseBsdf(Float4(0.5f)), {}, {})).index();
  CoatLayer textured = layer(0.0f, 0.01f);
  textured.roughness_texture = std::make_shared<SteppedRoughness>(0.0f, 0.3f);
  const CoatedDiffuseMaterial coated(constant_texture(0.5), ior, textured);
  CHECK(kind(coated, 0.25f) == closed);
  CHECK(kind(coated, 0.75f) == walk);
  // Where it reads 0.3, the same BSDF values as the number 0.3 (the walk's seed depends on the directions only);
  // where it reads 0, the smooth coat's closed form. Out-of-range readings are clamped to [0, 1].
  const CoatedDiffuseMaterial rough(constant_texture(0.5), ior, layer(0.3f, 0.01f));
  const CoatedDiffuseMaterial smooth(constant_texture(0.5), ior, layer(0.0f, 0.01f));
  CoatLayer too_rough = layer(0.0f, 0.01f);
  too_rough.roughness_texture = std::make_shared<SteppedRoughness>(-2.0f, 7.0f);
  const CoatedDiffuseMaterial clamped(constant_texture(0.5), ior, too_rough);
  const CoatedDiffuseMaterial one(constant_texture(0.5), ior, layer(1.0f, 0.01f));
  const Vec3 wo = normalize(Vec3{0.2f, -0.4f, 0.8f});
  for (const Vec3 wi : {Vec3{0, 0, 1}, normalize(Vec3{0.3f, 0.1f, 0.9f}), normalize(Vec3{-0.6f, 0.2f, 0.5f})}) {
    const auto eval = [&](const Material& m, float u) { return m.bsdf(MaterialContext::at_uv({u, 0.5f}), kLambda).eval(wo, wi); };
    for (int l = 0; l < 4; ++l) {
      CHECK(eval(coated, 0.75f)[l] == eval(rough, 0.75f)[l]);
      CHECK(eval(coated, 0.25f)[l] == eval(smooth, 0.25f)[l]);
      CHECK(eval(clamped, 0.75f)[l] == eval(one, 0.75f)[l]);
      CHECK(eval(clamped, 0.25f)[l] == eval(smooth, 0.25f)[l]);
    }
  }
}

TEST_CASE("material: a coated conductor's textured metal roughness is the numbers it reads") {
  const auto ior = std::make_shared<ConstantSpectrum>(1.5);
  const ComplexIorSpectra gold = conductor_ior(test::library(), "gold");
  const CoatedConductorMaterial numbers(ior, gold, 0.5f, 0.2f, layer(0.3f));
  const CoatedConductorMaterial textured = CoatedConductorMaterial(ior, gold, 0.0f, 0.0f, layer(0.3f))
                                               .with_conductor_roughness(std::make_shared<SteppedRoughness>(0.0f, 0.5f),
                                                                         std::make_shared<SteppedRoughness>(0.0f, 0.2f));
  const CoatedConductorMaterial smooth(ior, gold, 0.0f, 0.0f, layer(0.3f));
  const Vec3 wo = normalize(Vec3{0.2f, -0.4f, 0.8f});
  float textured_sum = 0.0f, smooth_sum = 0.0f;
  for (const Vec3 wi : {Vec3{0, 0, 1}, normalize(Vec3{0.3f, 0.1f, 0.9f}), normalize(Vec3{-0.6f, 0.2f, 0.5f})}) {
    const auto eval = [&](const CoatedConductorMaterial& m, float u) {
      return m.bsdf(MaterialContext::at_uv({u, 0.5f}), kLambda).eval(wo, wi);
    };
    for (int l = 0; l < 4; ++l) {
      CHECK(eval(textured, 0.75f)[l] == eval(numbers, 0.75f)[l]);
      CHECK(eval(textured, 0.25f)[l] == eval(smooth, 0.25f)[l]);
    }
    textured_sum += eval(textured, 0.75f)[0];
    smooth_sum += eval(smooth, 0.75f)[0];
  }
  // The texture matters: a rough metal under the coat is not the smooth one (one walk per evaluation may miss the
  // metal for some pairs of directions, so over the three).
  CHECK(textured_sum != smooth_sum);
  CHECK_THROWS_AS(CoatedConductorMaterial(ior, gold, 0.0f, 0.0f, {}).with_conductor_roughness(nullptr, nullptr), InputError);
}
