// Normal and bump maps (transport/textures/shading_normal_map.h): the frame they build, its fallbacks, and no NaN.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "transport/bsdfs/material.h"
#include "transport/textures/shading_normal_map.h"

using namespace rimu;

namespace shading_normal_map_test {

constexpr float kPi = 3.14159265358979f;

bool finite_unit(Vec3 n) {
  return std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) && std::fabs(length(n) - 1.0f) < 1e-5f;
}

// A linear displacement d = slope_u·u + slope_v·v.
class RampTexture final : public FloatTexture {
 public:
  RampTexture(float slope_u, float slope_v) : su_(slope_u), sv_(slope_v) {}
  float evaluate(const MaterialContext& c) const override { return su_ * c.uv.x + sv_ * c.uv.y; }

 private:
  float su_, sv_;
};

class ConstantNormalTexture final : public TangentNormalTexture {
 public:
  explicit ConstantNormalTexture(Vec3 n) : n_(n) {}
  Vec3 evaluate(Vec2) const override { return n_; }

 private:
  Vec3 n_;
};

MaterialContext flat_context(Vec3 dpdu, Vec3 dpdv) {
  MaterialContext c;
  c.uv = {0.3f, 0.6f};
  c.geometric_normal = c.shading_normal = {0, 0, 1};
  c.dpdu = dpdu;
  c.dpdv = dpdv;
  c.wo = {0, 0, 1};
  return c;
}

TEST_CASE("normal map: a flat map (rgb 0.5, 0.5, 1 → n = (0, 0, 1)) leaves the shading normal unchanged") {
  const Vec3 ns = normalize(Vec3{0.2f, -0.1f, 1.0f}), ng{0, 0, 1};
  const Vec3 n = map_tangent_normal(ns, ng, {1, 0, 0}, {2 * 0.5f - 1, 2 * 0.5f - 1, 2 * 1.0f - 1});
  CHECK(length(n - ns) < 1e-6f);
}

TEST_CASE("normal map: a tilted map tilts the normal by its angle, towards dp/du (x) and n × dp/du (y)") {
  const Vec3 ng{0, 0, 1};
  for (float tilt_deg : {10.0f, 30.0f, 60.0f}) {
    const float a = tilt_deg * kPi / 180.0f;
    // dp/du along +x, not unit and with a component along n (made orthogonal by the map).
    const Vec3 along_u = map_tangent_normal(ng, ng, {3, 0, 0.5f}, {std::sin(a), 0, std::cos(a)});
    CHECK(along_u.x == doctest::Approx(std::sin(a)).epsilon(1e-5));
    CHECK(along_u.y == doctest::Approx(0.0f).epsilon(1e-6));
    CHECK(along_u.z == doctest::Approx(std::cos(a)).epsilon(1e-5));
    // t = n × s = z × x = +y.
    const Vec3 along_t = map_tangent_normal(ng, ng, {3, 0, 0}, {0, std::sin(a), std::cos(a)});
    CHECK(along_t.y == doctest::Approx(std::sin(a)).epsilon(1e-5));
    CHECK(std::acos(dot(along_t, ng)) == doctest::Approx(a).epsilon(1e-4));
  }
  // An unnormalised map vector (8-bit rounding) is normalised.
  CHECK(finite_unit(map_tangent_normal(ng, ng, {1, 0, 0}, {0.3f, 0.1f, 0.7f})));
}

TEST_CASE("normal map: degenerate tangents fall back to the unmapped normal") {
  const Vec3 ns{0, 0, 1};
  const Vec3 tilted{0.5f, 0, 0.866f};
  CHECK(length(map_tangent_normal(ns, ns, {0, 0, 0}, tilted) - ns) == 0.0f);         // no uv parametrisation
  CHECK(length(map_tangent_normal(ns, ns, {0, 0, 2.0f}, tilted) - ns) == 0.0f);      // dp/du parallel to n
  CHECK(length(map_tangent_normal(ns, ns, {1e-5f, 0, 2.0f}, tilted) - ns) == 0.0f);  // within 1e-3 rad of n
  CHECK(length(map_tangent_normal(ns, ns, {1, 0, 0}, {0, 0, 0}) - ns) == 0.0f);       // a zero map vector
  CHECK(length(map_tangent_normal(ns, ns, {1, 0, 0}, {NAN, 0, 1}) - ns) == 0.0f);     // a NaN texel
  CHECK(length(map_tangent_normal(ns, ns, {INFINITY, 0, 0}, tilted) - ns) == 0.0f);   // an infinite tangent
  // Bump maps: zero, parallel tangents.
  const RampTexture ramp(0.5f, 0.0f);
  CHECK(length(bump_normal(flat_context({0, 0, 0}, {0, 1, 0}), ramp) - ns) == 0.0f);
  CHECK(length(bump_normal(flat_context({1, 0, 0}, {2, 0, 0}), ramp) - ns) == 0.0f);
}

TEST_CASE("normal map: a mapped normal below the geometric surface is bent back above it") {
  const Vec3 ng{0, 0, 1};
  // A map vector pointing 30° below the tangent plane along +x.
  const Vec3 n = map_tangent_normal(ng, ng, {1, 0, 0}, {std::cos(0.5236f), 0, -std::sin(0.5236f)});
  CHECK(finite_unit(n));
  CHECK(dot(n, ng) == doctest::Approx(kMinPerturbedCosine).epsilon(1e-3));
  CHECK(n.x > 0.99f);  // its tangential direction kept
  // Straight down: nothing tangential left to keep, the normal becomes ng.
  CHECK(length(keep_above_surface({0, 0, -1}, ng) - ng) < 1e-6f);
}

TEST_CASE("normal map: random frames and map vectors never give NaN, and stay above the surface") {
  std::mt19937 rng(15);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  auto random_vec = [&] { return Vec3{u(rng), u(rng), u(rng)}; };
  for (int i = 0; i < 20000; ++i) {
    const Vec3 ng = normalize(random_vec());
    Vec3 ns = normalize(ng + random_vec() * 0.5f);
    if (dot(ns, ng) <= 0.0f) ns = ng;
    // Every fourth tangent is (nearly) along the normal or zero.
    const Vec3 dpdu = i % 4 == 0 ? ns * u(rng) + random_vec() * 1e-7f : random_vec() * 10.0f;
    const Vec3 n = map_tangent_normal(ns, ng, dpdu, random_vec());
    REQUIRE(finite_unit(n));
    CHECK(dot(n, ng) >= kMinPerturbedCosine * 0.999f);
  }
}

TEST_CASE("bump map: a linear ramp of slope k tilts the normal by atan(k) against the rise") {
  const Vec3 dpdu{2, 0, 0}, dpdv{0, 0.5f, 0};  // p = (2u, 0.5v, 0): d/dx = slope_u / 2, d/dy = slope_v / 0.5
  for (float slope_u : {0.2f, 1.0f, 4.0f}) {
    const RampTexture ramp(slope_u, 0.0f);
    const Vec3 n = bump_normal(flat_context(dpdu, dpdv), ramp);
    // The surface z = (slope_u / 2)·x has normal (−slope_u/2, 0, 1)/|·|.
    const float k = slope_u / 2.0f;
    CHECK(finite_unit(n));
    CHECK(n.x == doctest::Approx(-k / std::sqrt(1 + k * k)).epsilon(1e-3));
    CHECK(n.z == doctest::Approx(1 / std::sqrt(1 + k * k)).epsilon(1e-3));
  }
  const RampTexture along_v(0.0f, 0.25f);
  const Vec3 n = bump_normal(flat_context(dpdu, dpdv), along_v);
  const float k = 0.25f / 0.5f;
  CHECK(n.y == doctest::Approx(-k / std::sqrt(1 + k * k)).epsilon(1e-3));
  // uv axes of the other handedness (v along −y): the normal stays on the shading normal's side.
  const Vec3 flipped = bump_normal(flat_context(dpdu, {0, -0.5f, 0}), along_v);
  CHECK(flipped.z > 0.0f);
  CHECK(flipped.y == doctest::Approx(k / std::sqrt(1 + k * k)).epsilon(1e-3));
  // A constant displacement changes nothing.
  const ConstantFloatTexture flat(0.7f);
  CHECK(length(bump_normal(flat_context(dpdu, dpdv), flat) - Vec3{0, 0, 1}) < 1e-6f);
}

TEST_CASE("material normal modifier: only materials with a map (or a mix of one) use tangents and change the normal") {
  auto grey = std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(0.5f));
  Material plain = DiffuseMaterial(grey);
  CHECK_FALSE(plain.uses_tangents());
  Material mapped = DiffuseMaterial(grey);
  const float a = 0.3f;
  mapped.set_normal_modifier(
      ShadingNormalModifier::normal_map(std::make_shared<ConstantNormalTexture>(Vec3{std::sin(a), 0, std::cos(a)})));
  CHECK(mapped.uses_tangents());
  const MaterialContext c = flat_context({1, 0, 0}, {0, 1, 0});
  CHECK(length(plain.shading_normal(c) - c.shading_normal) == 0.0f);
  CHECK(std::acos(mapped.shading_normal(c).z) == doctest::Approx(a).epsilon(1e-4));
  // A mix that always chooses the mapped material uses its map.
  Material mix = MixMaterial(std::make_shared<Material>(plain), std::make_shared<Material>(mapped),
                             std::make_shared<ConstantFloatTexture>(1.0f), 7);
  CHECK(mix.uses_tangents());
  CHECK(std::acos(mix.shading_normal(c).z) == doctest::Approx(a).epsilon(1e-4));
}

}  // namespace shading_normal_map_test
