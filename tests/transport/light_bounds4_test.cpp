// The 4-wide importance (transport/lights/light_bounds4.h) is bit for bit the scalar light_importance in every lane:
// the light tree's pruning relies on a child scoring > 0 exactly where its scalar importance does (a witness leaf
// found by the scalar search must score in the 4-wide split too, or its light would lose its probability).
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <random>

#include "light_test_support.h"
#include "transport/lights/light_bounds4.h"

using namespace rimu;

namespace {

Vec3 random_point(std::mt19937& rng, float extent) {
  return {extent * (2 * test::uniform01(rng) - 1), extent * (2 * test::uniform01(rng) - 1),
          extent * (2 * test::uniform01(rng) - 1)};
}

// Bounds of every kind the tree holds: points (spots, IES cones, half-space downlights), one- and two-sided
// triangles, and clusters of them (wide cones, boxes that p may be inside).
LightBounds random_bounds(std::mt19937& rng) {
  const int kind = int(test::uniform01(rng) * 4.0f);
  const Vec3 p = random_point(rng, 2.0f);
  if (kind == 0)
    return point_light_bounds(p, 0.1 + 10 * test::uniform01(rng), test::uniform_sphere_direction(rng), 3.2 * test::uniform01(rng),
                              0.5 * test::uniform01(rng));
  const Vec3 a = p + random_point(rng, 0.3f), b = p + random_point(rng, 0.3f);
  const Vec3 normal = normalize(cross(a - p, b - p));
  const LightBounds triangle = triangle_light_bounds(p, a, b, normal, 0.5 * length(cross(a - p, b - p)),
                                                     1.0 + test::uniform01(rng), kind == 2);
  if (kind != 3) return triangle;
  return unite(triangle, point_light_bounds(random_point(rng, 2.0f), 1.0, test::uniform_sphere_direction(rng), 0.7, 0.2));
}

}  // namespace

TEST_CASE("light bounds, 4 wide: every lane equals the scalar importance bit for bit") {
  std::mt19937 rng(4);
  int scored = 0, zero = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    ImportanceBounds4 four;
    std::array<ImportanceBounds, 4> one;
    const int lanes = 1 + trial % 4;  // unused lanes must score 0
    for (int j = 0; j < lanes; ++j) {
      one[size_t(j)] = ImportanceBounds::of(random_bounds(rng));
      four.set(j, one[size_t(j)]);
    }
    Vec3 p = random_point(rng, 2.5f);
    if (trial % 7 == 0) p = one[0].centre_m + random_point(rng, 0.05f);  // inside a bounding sphere
    const Vec3 normal = trial % 5 == 0 ? Vec3{} : test::uniform_sphere_direction(rng);
    const std::array<float, 4> wide = light_importance4(four, p, normal).value;
    for (int j = 0; j < 4; ++j) {
      const float scalar = j < lanes ? light_importance(one[size_t(j)], p, normal) : 0.0f;
      INFO("trial " << trial << " lane " << j << ": " << wide[size_t(j)] << " vs " << scalar);
      CHECK(std::bit_cast<uint32_t>(wide[size_t(j)]) == std::bit_cast<uint32_t>(scalar));
      if (j < lanes) (scalar > 0.0f ? scored : zero) += 1;
    }
  }
  // Both outcomes occur often (each early-out of the scalar code is exercised).
  CHECK(scored > 5000);
  CHECK(zero > 5000);
}

TEST_CASE("light bounds, 4 wide: the certificate holds only where the member scores, and often there") {
  // For one emitter's own bounds the certificate says the emitter scores > 0 at the point: it must never be set
  // where the scalar importance is 0, and it should be set at most points where the emitter scores with margin.
  std::mt19937 rng(44);
  int certified = 0, scoring = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    ImportanceBounds4 four;
    std::array<ImportanceBounds, 4> one;
    for (int j = 0; j < 4; ++j) {
      const int kind = j % 2;
      const Vec3 p = random_point(rng, 2.0f);
      const Vec3 a = p + random_point(rng, 0.3f), b = p + random_point(rng, 0.3f);
      const LightBounds bounds =
          kind == 0 ? point_light_bounds(p, 1.0, test::uniform_sphere_direction(rng), 1.5 * test::uniform01(rng), 0.3 * test::uniform01(rng))
                    : triangle_light_bounds(p, a, b, normalize(cross(a - p, b - p)),
                                            0.5 * length(cross(a - p, b - p)), 1.0, false);
      one[size_t(j)] = ImportanceBounds::of(bounds);
      four.set(j, one[size_t(j)]);
    }
    const Vec3 p = random_point(rng, 3.0f);
    const Vec3 normal = trial % 5 == 0 ? Vec3{} : test::uniform_sphere_direction(rng);
    const Importance4 wide = light_importance4(four, p, normal);
    for (int j = 0; j < 4; ++j) {
      const bool is_certified = (wide.certified >> j) & 1;
      const float scalar = light_importance(one[size_t(j)], p, normal);
      INFO("trial " << trial << " lane " << j);
      if (is_certified) CHECK(scalar > 0.0f);
      certified += is_certified;
      scoring += scalar > 0.0f;
    }
  }
  CHECK(certified > scoring / 2);
}

TEST_CASE("light bounds, 4 wide: light_scores4 holds exactly where the scalar importance is > 0") {
  // The light tree checks its slots' representatives with it instead of the importance: a lane it passes must score
  // (or a slot with no scoring leaf would keep its probability), and one it fails must not (or a light would lose it).
  std::mt19937 rng(7);
  int scored = 0, zero = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    ImportanceBounds4 four;
    std::array<ImportanceBounds, 4> one;
    const int lanes = 1 + trial % 4;
    for (int j = 0; j < lanes; ++j) {
      one[size_t(j)] = ImportanceBounds::of(random_bounds(rng));
      four.set(j, one[size_t(j)]);
    }
    Vec3 p = random_point(rng, 2.5f);
    if (trial % 7 == 0) p = one[0].centre_m + random_point(rng, 0.05f);  // inside a bounding sphere
    if (trial % 11 == 0) p = one[0].centre_m;                            // at a point light's centre
    const Vec3 normal = trial % 5 == 0 ? Vec3{} : test::uniform_sphere_direction(rng);
    const int scores = light_scores4(four, p, normal);
    for (int j = 0; j < 4; ++j) {
      const bool scalar = j < lanes && light_importance(one[size_t(j)], p, normal) > 0.0f;
      INFO("trial " << trial << " lane " << j);
      CHECK(bool((scores >> j) & 1) == scalar);
      if (j < lanes) (scalar ? scored : zero) += 1;
    }
  }
  CHECK(scored > 5000);
  CHECK(zero > 5000);
}
