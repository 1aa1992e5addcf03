// Perlin noise, pbrt-v4's procedural textures (fbm, wrinkled, windy, dots, marble, 3D checkerboard) and its texture
// mappings, against their definitions and against values printed by pbrt-v4's own Noise().
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "spectral/error.h"
#include "transport/textures/perlin_noise.h"
#include "transport/textures/procedural_texture.h"
#include "test_support.h"

using namespace rimu;

namespace {

MaterialContext at(Vec3 p) {
  MaterialContext c;
  c.position = p;
  return c;
}

FloatTexturePtr constant(float v) { return std::make_shared<ConstantFloatTexture>(v); }

using rimu::test::kLambda;

}  // namespace

TEST_CASE("Perlin noise: pbrt-v4's values, zero on the lattice, bounded and continuous") {
  // pbrt::Noise(x, y, z) of pbrt-v4 (built from its sources, float) at these points: the same table and gradients.
  struct Reference {
    Vec3 p;
    float noise;
  };
  for (const Reference& r : {Reference{{0.5f, 0.5f, 0.5f}, -0.125f}, Reference{{1.25f, 2.75f, 0.125f}, 0.268567562f},
                             Reference{{-3.3f, 7.1f, 12.9f}, -0.0430220962f},
                             Reference{{100.37f, -42.61f, 0.83f}, 0.35795477f},
                             Reference{{0.1f, 0.2f, 0.3f}, 0.358721048f}}) {
    CAPTURE(r.p.x);
    CHECK(perlin_noise(r.p) == doctest::Approx(r.noise).epsilon(1e-5));
  }
  // Zero at every lattice point: every corner's offset is zero there and the fade weights pick that corner alone.
  for (int x = -3; x <= 3; ++x)
    for (int y = -2; y <= 2; ++y)
      for (int z = 250; z <= 258; z += 4) CHECK(perlin_noise(Vec3{float(x), float(y), float(z)}) == 0.0f);

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-50.0f, 50.0f), unit(-1.0f, 1.0f);
  float largest = 0.0f, steepest = 0.0f;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p{coordinate(rng), coordinate(rng), coordinate(rng)};
    const float n = perlin_noise(p);
    largest = std::max(largest, std::fabs(n));
    // Continuity: a step of 1e-3 moves the value by at most |∇n|·1e-3; |∇n| ≤ 2·(1 + 3·1.875) < 16 (corner terms
    // ≤ 2 with slope ≤ 1 each way, fade slope ≤ 15/8): also across cell faces, where a jump would show.
    Vec3 step{unit(rng), unit(rng), unit(rng)};
    step = step * (1e-3f / std::max(1e-6f, length(step)));
    steepest = std::max(steepest, std::fabs(perlin_noise(p + step) - n) / 1e-3f);
  }
  CHECK(largest <= 2.0f);
  CHECK(largest > 0.5f);  // and not trivially small
  CHECK(steepest < 16.0f);
  // Across a cell face exactly: left and right limits agree.
  CHECK(perlin_noise(Vec3{3.0f - 1e-5f, 0.3f, 0.7f}) == doctest::Approx(perlin_noise(Vec3{3.0f, 0.3f, 0.7f})).epsilon(1e-3));
  // Non-finite points (a degenerate placement) give the lattice value rather than undefined integer conversions.
  CHECK(perlin_noise(Vec3{std::nanf(""), 0.0f, 0.0f}) == 0.0f);
  CHECK(perlin_noise(Vec3{1e30f, -1e30f, 3.5f}) == perlin_noise(Vec3{std::fmod(1e30f, float(1 << 30)), std::fmod(-1e30f, float(1 << 30)), 3.5f}));
}

TEST_CASE("Perlin noise, four lanes: every lane the scalar noise's bits, including the awkward points") {
  // perlin_noise4 feeds the cloud medium, whose images must not change with it: compare bit patterns.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> near(-40.0f, 40.0f), wide(-3e9f, 3e9f);
  std::vector<Vec3> points;
  for (int i = 0; i < 20000; ++i) points.push_back({near(rng), near(rng), near(rng)});
  for (int i = 0; i < 400; ++i) points.push_back({wide(rng), near(rng), wide(rng)});  // beyond the 2³⁰ wrap
  // Lattice points, their negative zero and half-way points, cells at the permutation's wrap (255 → 256).
  for (float v : {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 255.0f, 255.999f, 256.0f, -256.5f, 1073741823.0f})
    points.push_back({v, -v, 0.25f * v});
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  points.push_back({nan, 1.0f, 2.0f});
  points.push_back({1.5f, inf, 2.0f});
  points.push_back({1.5f, 2.5f, -inf});
  while (points.size() % 4) points.push_back({0.3f, 0.7f, 0.1f});
  size_t different = 0;
  for (size_t i = 0; i < points.size(); i += 4) {
    const Float4 x(points[i].x, points[i + 1].x, points[i + 2].x, points[i + 3].x);
    const Float4 y(points[i].y, points[i + 1].y, points[i + 2].y, points[i + 3].y);
    const Float4 z(points[i].z, points[i + 1].z, points[i + 2].z, points[i + 3].z);
    const auto lanes = perlin_noise4(x, y, z).to_array();
    for (size_t k = 0; k < 4; ++k)
      if (std::bit_cast<uint32_t>(lanes[k]) != std::bit_cast<uint32_t>(perlin_noise(points[i + k]))) ++different;
  }
  CHECK(different == 0);
  // fbm and turbulence take their octaves four at a time: the same bits as the plain scalar sums.
  size_t sums_different = 0;
  for (size_t i = 0; i < 2000; ++i) {
    const Vec3 p = points[i];
    for (const int octaves : {0, 1, 3, 4, 5, 8, 30}) {
      const float omega = 0.3f + 0.1f * float(octaves % 5);
      float sum = 0.0f, abs_sum = 0.0f, frequency = 1.0f, weight = 1.0f;
      for (int k = 0; k < octaves; ++k, frequency *= 1.99f, weight *= omega) {
        sum += weight * perlin_noise(p * frequency);
        abs_sum += weight * std::fabs(perlin_noise(p * frequency));
      }
      abs_sum += weight * 0.2f;
      sums_different += std::bit_cast<uint32_t>(fbm(p, omega, octaves)) != std::bit_cast<uint32_t>(sum);
      sums_different += std::bit_cast<uint32_t>(turbulence(p, omega, octaves)) != std::bit_cast<uint32_t>(abs_sum);
    }
  }
  CHECK(sums_different == 0);
}

TEST_CASE("fbm, turbulence, windy: the octave sums of pbrt-v4's FBm and Turbulence at full resolution") {
  const Vec3 p{0.3f, -1.7f, 2.2f};
  const float n0 = perlin_noise(p), n1 = perlin_noise(p * 1.99f), n2 = perlin_noise(p * (1.99f * 1.99f));
  CHECK(fbm(p, 0.6f, 3) == doctest::Approx(n0 + 0.6f * n1 + 0.36f * n2).epsilon(1e-6));
  CHECK(fbm(p, 0.6f, 0) == 0.0f);
  // Turbulence adds 0.2·ω^octaves: pbrt's stand-in for the octaves it does not evaluate.
  CHECK(turbulence(p, 0.6f, 3) ==
        doctest::Approx(std::fabs(n0) + 0.6f * std::fabs(n1) + 0.36f * std::fabs(n2) + 0.2f * 0.216f).epsilon(1e-6));
  CHECK(turbulence(p, 0.6f, 0) == doctest::Approx(0.2f));

  // The textures read the point in texture space: placed by a translation, the same values appear shifted.
  const Transform placed = Transform::translate({10, 20, 30});
  const NoiseFloatTexture fbm_texture(NoiseFloatTexture::Kind::fbm, {3, 0.6f}, placed.inverse());
  const NoiseFloatTexture wrinkled(NoiseFloatTexture::Kind::wrinkled, {3, 0.6f}, placed.inverse());
  const NoiseFloatTexture windy(NoiseFloatTexture::Kind::windy, {}, placed.inverse());
  const MaterialContext c = at(placed.point(p));
  CHECK(fbm_texture.evaluate(c) == doctest::Approx(fbm(p, 0.6f, 3)).epsilon(1e-5));
  CHECK(wrinkled.evaluate(c) == doctest::Approx(turbulence(p, 0.6f, 3)).epsilon(1e-5));
  CHECK(windy.evaluate(c) == doctest::Approx(std::fabs(fbm(0.1f * p, 0.5f, 3)) * fbm(p, 0.5f, 6)).epsilon(1e-5));
  CHECK_THROWS_AS(NoiseFloatTexture(NoiseFloatTexture::Kind::fbm, {31, 0.5f}, Transform()), InputError);
  CHECK_THROWS_AS(NoiseFloatTexture(NoiseFloatTexture::Kind::fbm, {-1, 0.5f}, Transform()), InputError);
  CHECK_THROWS_AS(NoiseFloatTexture(NoiseFloatTexture::Kind::fbm, {8, 10.5f}, Transform()), InputError);
  // A marble whose phase overflows (sin(∞) = NaN) picks the ramp's first colour instead of indexing with NaN.
  const MarbleSpectralTexture overflowing({{2, 0.5f}, 1e30f, 1e30f}, Transform(), nullptr);
  const SampledSpectrum first = overflowing.evaluate_at(at({0.0f, 1e9f, 0.0f}), kLambda);  // q_y = 1e39: ∞ in float
  CHECK(first[0] == doctest::Approx(marble_colour(0.0f).r));
}

TEST_CASE("polka dots: inside only in cells whose noise is positive, within 0.35 of the shifted centre") {
  int cells_with_dots = 0;
  for (int s = -20; s < 20; ++s)
    for (int t = -20; t < 20; ++t) {
      const float fs = float(s), ft = float(t);
      const bool has_dot = perlin_noise(fs + 0.5f, ft + 0.5f) > 0.0f;
      const float cs = fs + 0.15f * perlin_noise(fs + 1.5f, ft + 2.8f);
      const float ct = ft + 0.15f * perlin_noise(fs + 4.5f, ft + 9.8f);
      cells_with_dots += has_dot;
      CHECK(inside_polka_dot({cs, ct}) == has_dot);                       // the centre
      CHECK(inside_polka_dot({cs + 0.34f, ct}) == has_dot);               // just inside the radius
      CHECK_FALSE(inside_polka_dot({cs + 0.36f * 0.7071f, ct + 0.36f * 0.7071f}));  // just outside
    }
  // Noise at (n + ½, m + ½, ½) is positive about as often as negative.
  CHECK(cells_with_dots > 1600 / 4);
  CHECK(cells_with_dots < 1600 * 3 / 4);

  // The texture picks inside/outside by the mapped coordinates (uv here: s = 2u).
  const DotsFloatTexture dots(constant(1.0f), constant(0.0f), UvMapping{2, 1, 0, 0});
  MaterialContext c;
  for (float u : {0.1f, 0.37f, 0.8f, 1.9f})
    for (float v : {0.2f, 0.55f, 3.1f}) {
      c.uv = {u, v};
      CHECK(dots.evaluate(c) == (inside_polka_dot({2 * u, v}) ? 1.0f : 0.0f));
    }
}

TEST_CASE("marble: pbrt-v4's colour ramp and ramp position") {
  // Segment ends are control points (×1.5): t = 0 the first, t = ½ the fourth (mid grey), t = 1 the ninth.
  const Rgb first = marble_colour(0.0f), middle = marble_colour(0.5f), last = marble_colour(1.0f);
  CHECK(first.r == doctest::Approx(0.87));
  CHECK(first.b == doctest::Approx(0.9));
  CHECK(middle.r == doctest::Approx(0.75));
  CHECK(middle.g == doctest::Approx(0.75));
  CHECK(last.b == doctest::Approx(0.9));
  // Inside the fifth segment (points 4-7: t in [4/6, 5/6]): at its middle, (p4 + 3p5 + 3p6 + p7)/8 × 1.5.
  const Rgb dark = marble_colour(0.75f);
  CHECK(dark.r == doctest::Approx(1.5 * (0.6 + 3 * 0.58 + 3 * 0.58 + 0.2) / 8).epsilon(1e-6));
  CHECK(dark.b == doctest::Approx(1.5 * (0.58 + 3 * 0.6 + 3 * 0.6 + 0.33) / 8).epsilon(1e-6));
  for (float t = 0.0f; t <= 1.0f; t += 0.01f) {
    const Rgb c = marble_colour(t);
    for (double v : {c.r, c.g, c.b}) {
      CHECK(v >= 0.3 - 1e-6);
      CHECK(v <= 0.9 + 1e-6);
    }
  }
  const MarbleParameters m{{4, 0.5f}, 2.0f, 0.3f};
  const Vec3 p{0.4f, 1.1f, -0.2f};
  CHECK(marble_ramp_position(p, m) == doctest::Approx(0.5f + 0.5f * std::sin(2.2f + 0.3f * fbm(p * 2.0f, 0.5f, 4))).epsilon(1e-6));

  // In rgb transport the lanes carry the ramp's colour (table-interpolated).
  const MarbleSpectralTexture rgb_lanes(m, Transform(), nullptr);
  const SampledSpectrum s = rgb_lanes.evaluate_at(at(p), kLambda);
  const Rgb expected = marble_colour(marble_ramp_position(p, m));
  CHECK(s[0] == doctest::Approx(expected.r).epsilon(1e-4));
  CHECK(s[2] == doctest::Approx(expected.b).epsilon(1e-4));
}

TEST_CASE("texture mappings: spherical, cylindrical, planar and solid, placed by a transform") {
  constexpr float kPi = std::numbers::pi_v<float>;
  TextureMapping spherical;
  spherical.kind = TextureMapping::Kind::spherical;
  spherical.texture_from_world = Transform::translate({1, 2, 3}).inverse();
  const auto st = [](const TextureMapping& m, Vec3 p) { return m.st(at(p)); };
  // s = θ/π from +z, t = φ/2π.
  CHECK(st(spherical, {1, 2, 5}).x == doctest::Approx(0.0f));
  CHECK(st(spherical, {1, 2, 0}).x == doctest::Approx(1.0f));
  CHECK(st(spherical, {3, 2, 3}).x == doctest::Approx(0.5f));
  CHECK(st(spherical, {3, 2, 3}).y == doctest::Approx(0.0f));
  CHECK(st(spherical, {1, 4, 3}).y == doctest::Approx(0.25f));
  CHECK(st(spherical, {1, 0, 3}).y == doctest::Approx(0.75f));
  CHECK(st(spherical, {2, 3, 3 + std::sqrt(2.0f)}).x == doctest::Approx(0.25f));

  TextureMapping cylindrical;
  cylindrical.kind = TextureMapping::Kind::cylindrical;
  CHECK(st(cylindrical, {1, 0, 0.7f}).x == doctest::Approx(0.5f));  // (π + 0)/2π
  CHECK(st(cylindrical, {1, 0, 0.7f}).y == doctest::Approx(0.7f));
  CHECK(st(cylindrical, {0, 1, 0}).x == doctest::Approx((kPi + kPi / 2) / (2 * kPi)));

  TextureMapping planar;
  planar.kind = TextureMapping::Kind::planar;
  planar.planar_s = {0, 0, 2};
  planar.planar_t = {1, 1, 0};
  planar.planar_offset = {0.5f, -1};
  planar.texture_from_world = Transform::scale({2, 2, 2}).inverse();
  CHECK(st(planar, {2, 4, 6}).x == doctest::Approx(0.5f + 6));  // texture point (1, 2, 3)
  CHECK(st(planar, {2, 4, 6}).y == doctest::Approx(-1.0f + 3));

  // A solid checkerboard: unit cubes of the texture-space point, the first texture where ⌊x⌋ + ⌊y⌋ + ⌊z⌋ is even.
  const TextureMapping solid = TextureMapping::solid(Transform::translate({0.5f, 0, 0}).inverse());
  const CheckerboardFloatTexture cubes(constant(1.0f), constant(2.0f), solid);
  CHECK(cubes.evaluate(at({1.0f, 0.5f, 0.5f})) == 1.0f);   // (0.5, 0.5, 0.5)
  CHECK(cubes.evaluate(at({2.0f, 0.5f, 0.5f})) == 2.0f);   // (1.5, …)
  CHECK(cubes.evaluate(at({2.0f, 1.5f, 0.5f})) == 1.0f);
  CHECK(cubes.evaluate(at({2.0f, 1.5f, -0.5f})) == 2.0f);  // ⌊−0.5⌋ = −1
  CHECK(cubes.evaluate(at({0.0f, 0.5f, 0.5f})) == 2.0f);   // x = −0.5
  CHECK(cubes.evaluate(at({1e30f, 0.5f, 0.5f})) == 1.0f);  // huge coordinates are even, no integer overflow
}
