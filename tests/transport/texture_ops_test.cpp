// Float textures and the texture combinators (pbrt-v4's scale, mix, directionmix, checkerboard), against values
// worked by hand from pbrt-v4's definitions.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/error.h"
#include "spectral/library/optical_constants.h"
#include "test_support.h"
#include "transport/textures/float_texture.h"
#include "transport/bsdfs/material.h"
#include "transport/textures/spectral_texture_ops.h"

using namespace rimu;

namespace {

FloatTexturePtr constant(float v) { return std::make_shared<ConstantFloatTexture>(v); }
SpectralTexturePtr spectral(double v) {
  return std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(v));
}

// A float texture that is u itself: makes the combinators' per-point behaviour visible.
class UTexture final : public FloatTexture {
 public:
  float evaluate(const MaterialContext& c) const override { return c.uv.x; }
};

using rimu::test::kLambda;

MaterialContext with_normal(Vec3 n) {
  MaterialContext c;
  c.geometric_normal = c.shading_normal = n;
  return c;
}

}  // namespace

TEST_CASE("float textures: product, mix, direction mix and checkerboard") {
  const auto u = std::make_shared<UTexture>();
  const MaterialContext at_03 = MaterialContext::at_uv({0.3f, 0.8f});
  CHECK(ProductFloatTexture(u, constant(2.0f)).evaluate(at_03) == doctest::Approx(0.6f));
  // pbrt-v4's mix: (1 − t)·tex1 + t·tex2; here t = u = 0.3.
  CHECK(MixFloatTexture(constant(1.0f), constant(5.0f), u).evaluate(at_03) == doctest::Approx(0.7f * 1.0f + 0.3f * 5.0f));
  // directionmix: w = |n·dir|, w·tex1 + (1 − w)·tex2; the direction is normalised; either side of the surface.
  const DirectionMixFloatTexture dm(constant(1.0f), constant(3.0f), {0.0f, 2.0f, 0.0f});
  CHECK(dm.evaluate(with_normal({0, 1, 0})) == doctest::Approx(1.0f));
  CHECK(dm.evaluate(with_normal({0, -1, 0})) == doctest::Approx(1.0f));
  CHECK(dm.evaluate(with_normal({1, 0, 0})) == doctest::Approx(3.0f));
  CHECK(dm.evaluate(with_normal({0.6f, 0.8f, 0})) == doctest::Approx(0.8f * 1.0f + 0.2f * 3.0f));
  CHECK_THROWS_AS(DirectionMixFloatTexture(constant(1.0f), constant(3.0f), {0, 0, 0}), InputError);
  // checkerboard, uscale = vscale = 4: squares of 1/4; tex1 where ⌊4u⌋ + ⌊4v⌋ is even.
  const CheckerboardFloatTexture board(constant(1.0f), constant(2.0f), UvMapping{4, 4, 0, 0});
  CHECK(board.evaluate(MaterialContext::at_uv({0.1f, 0.1f})) == 1.0f);
  CHECK(board.evaluate(MaterialContext::at_uv({0.3f, 0.1f})) == 2.0f);
  CHECK(board.evaluate(MaterialContext::at_uv({0.3f, 0.3f})) == 1.0f);
  CHECK(board.evaluate(MaterialContext::at_uv({-0.1f, 0.1f})) == 2.0f);  // ⌊−0.4⌋ = −1: odd, not truncated towards zero
  // Offsets shift the board: udelta 1 swaps the squares.
  CHECK(CheckerboardFloatTexture(constant(1.0f), constant(2.0f), UvMapping{4, 4, 1, 0}).evaluate(MaterialContext::at_uv({0.1f, 0.1f})) == 2.0f);
}

TEST_CASE("spectral textures: the same combinators per lane, and uv-only lookups") {
  const auto u = std::make_shared<UTexture>();
  const MaterialContext at_03 = MaterialContext::at_uv({0.3f, 0.8f});
  const Float4 scaled = ProductSpectralTexture(spectral(0.5), constant(0.4f)).evaluate_at(at_03, kLambda);
  CHECK(scaled[0] == doctest::Approx(0.2f));
  const Float4 mixed = MixSpectralTexture(spectral(0.2), spectral(0.6), u).evaluate_at(at_03, kLambda);
  CHECK(mixed[3] == doctest::Approx(0.7f * 0.2f + 0.3f * 0.6f));
  const Float4 dm = DirectionMixSpectralTexture(spectral(0.2), spectral(0.6), {0, 0, 1}).evaluate_at(with_normal({0.8f, 0, 0.6f}), kLambda);
  CHECK(dm[1] == doctest::Approx(0.6f * 0.2f + 0.4f * 0.6f));
  const CheckerboardSpectralTexture board(spectral(0.1), spectral(0.9), UvMapping{2, 2, 0, 0});
  CHECK(board.evaluate({0.7f, 0.2f}, kLambda)[2] == doctest::Approx(0.9f));  // uv-only lookup: ⌊1.4⌋ + ⌊0.4⌋ = 1
  CHECK(board.evaluate_at(MaterialContext::at_uv({0.7f, 0.7f}), kLambda)[2] == doctest::Approx(0.1f));
}

TEST_CASE("materials: textured roughness and pbrt-v4's conductor by reflectance") {
  // A checkerboard of smooth and rough squares: the BSDF is a delta lobe on the smooth ones only.
  const auto board = std::make_shared<CheckerboardFloatTexture>(constant(0.0f), constant(0.5f), UvMapping{2, 2, 0, 0});
  const Material metal = ConductorMaterial(conductor_ior(test::library(), "gold"), board, board);
  const Material glass = DielectricMaterial(std::make_shared<ConstantSpectrum>(1.5), board, board);
  for (const Material* m : {&metal, &glass}) {
    CHECK(m->bsdf(MaterialContext::at_uv({0.2f, 0.2f}), kLambda).flags().has_delta);
    CHECK(!m->bsdf(MaterialContext::at_uv({0.7f, 0.2f}), kLambda).flags().has_delta);
  }
  // Roughness beyond [0, 1] (a scaled texture) is clamped, NaN taken as smooth: no throw, no NaN lobe.
  const Material clamped = ConductorMaterial(conductor_ior(test::library(), "gold"), constant(7.0f), constant(NAN));
  CHECK(!clamped.bsdf({}, kLambda).flags().has_delta);

  // Smooth, by reflectance r: n = 1, k = 2√(r/(1 − r)) reflects exactly r at normal incidence.
  for (double r : {0.04, 0.5, 0.95}) {
    const Material m = ConductorMaterial::from_reflectance(spectral(r), constant(0.0f), constant(0.0f));
    const auto s = m.bsdf({}, kLambda).sample({0.0f, 0.0f, 1.0f}, 0.5f, {0.5f, 0.5f});
    REQUIRE(s);
    for (int lane = 0; lane < 4; ++lane) CHECK(s->f[lane] * std::fabs(s->wi.z) / s->pdf[lane] == doctest::Approx(r).epsilon(1e-4));
  }
  // r = 1 would need k = ∞: clamped to 0.9999 as pbrt-v4 does (finite, not NaN).
  const auto full = ConductorMaterial::from_reflectance(spectral(1.0), constant(0.0f), constant(0.0f)).bsdf({}, kLambda).sample({0, 0, 1}, 0.5f, {0.5f, 0.5f});
  REQUIRE(full);
  CHECK(std::isfinite(full->f[0]));
  CHECK(full->f[0] * std::fabs(full->wi.z) / full->pdf[0] == doctest::Approx(0.9999).epsilon(1e-4));
}
