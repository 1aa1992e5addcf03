// The light BVH (transport/lights/bvh_light_sampler.h): at random shading points of three scenes the sampled frequencies
// match pmf() (chi-square over every light part plus "no light"), pmf() is bit-identical to the probability
// sample() returns, the probabilities sum to 1 and a part has probability > 0 exactly where its own bounds score
// > 0; nothing behind a one-sided emitter, outside a spot's or IES light's cone or below an opaque surface is ever
// chosen; an environment gets the fixed rule's share, a sun one that follows its irradiance against the tree's
// importance at the point, never below the rule's floor.
#include <doctest/doctest.h>

#include <algorithm>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "light_test_support.h"
#include "transport/lights/area_light.h"
#include "transport/lights/bvh_light_sampler.h"
#include "transport/lights/candela_distribution.h"
#include "transport/lights/distant_light.h"
#include "transport/lights/environment_light.h"
#include "transport/lights/goniometric_light.h"
#include "transport/lights/point_light.h"
#include "spectral/wavelengths/sampled_wavelengths.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "transport/lights/spot_light.h"

using namespace rimu;

namespace {

LightSpectrum flat(double scale) { return LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), scale); }

struct TestScene {
  std::vector<std::unique_ptr<Light>> lights;
  std::vector<const Light*> pointers() const {
    std::vector<const Light*> p;
    for (const auto& l : lights) p.push_back(l.get());
    return p;
  }
};

Vec3 random_in_box(std::mt19937& rng, Vec3 lower, Vec3 upper) {
  return {lower.x + (upper.x - lower.x) * test::uniform01(rng), lower.y + (upper.y - lower.y) * test::uniform01(rng),
          lower.z + (upper.z - lower.z) * test::uniform01(rng)};
}

std::shared_ptr<const CandelaDistribution> downlight_table() {
  // γ = 0-60° lit, 90° and beyond dark: the light reaches γ < 90°.
  const std::vector<double> gamma = {0, 30, 60, 90, 120, 180};
  const std::vector<double> c = {0, 360};
  const std::vector<double> row = {100, 80, 30, 0, 0, 0};
  std::vector<double> values = row;
  values.insert(values.end(), row.begin(), row.end());
  return std::make_shared<CandelaDistribution>(gamma, c, values);
}

// A room: a one-sided ceiling quad facing down, a point light, a spot and an IES downlight, a two-sided panel.
TestScene room_scene() {
  TestScene s;
  const std::vector<Vec3> quad = {{-0.5f, 2, -0.5f}, {0.5f, 2, -0.5f}, {0.5f, 2, 0.5f}, {-0.5f, 2, 0.5f}};
  const std::vector<uint32_t> down = {0, 1, 2, 0, 2, 3};  // (v1−v0)×(v2−v0) = −y: faces down
  s.lights.push_back(std::make_unique<AreaLight>(quad, down, flat(5.0), false));
  s.lights.push_back(std::make_unique<PointLight>(Vec3{1.5f, 1.5f, 0}, flat(0.2)));
  s.lights.push_back(std::make_unique<SpotLight>(Vec3{-1.5f, 1.9f, 1}, Vec3{0, -1, 0}, 20.0, 30.0, flat(1.0)));
  s.lights.push_back(std::make_unique<GoniometricLight>(Vec3{0, 1.9f, -1.5f}, Vec3{0, -1, 0}, Vec3{1, 0, 0},
                                                        flat(0.01), downlight_table()));
  const std::vector<Vec3> panel = {{2, 0.5f, -0.5f}, {2, 0.5f, 0.5f}, {2, 1.5f, 0.5f}};
  const std::vector<uint32_t> one = {0, 1, 2};
  s.lights.push_back(std::make_unique<AreaLight>(panel, one, flat(1.0), true));
  return s;
}

// Outdoors: lights at infinity (an environment, a sun) with a spot and a point light; `scale` stretches positions.
TestScene outdoor_scene(float scale = 1.0f) {
  TestScene s;
  s.lights.push_back(std::make_unique<EnvironmentLight>(flat(0.02)));
  s.lights.push_back(std::make_unique<SpotLight>(Vec3{0, 2, 0} * scale, Vec3{0, -1, 0}, 25.0, 35.0, flat(0.5)));
  s.lights.push_back(std::make_unique<DistantLight>(Vec3{0.3f, 1, 0.2f}, flat(1.0), 0.53));
  s.lights.push_back(std::make_unique<PointLight>(Vec3{3, 0.5f, 2} * scale, flat(0.05)));
  return s;
}

struct Triangle {
  Vec3 v0, v1, v2;
};

// 1,000 one-sided triangles of random size, place and orientation, 50 two-sided ones and three point lights.
TestScene many_scene(std::vector<Triangle>* one_sided = nullptr) {
  TestScene s;
  std::mt19937 rng(7);
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;
  for (int k = 0; k < 1000; ++k) {
    const Vec3 c = random_in_box(rng, {-5, 0, -5}, {5, 4, 5});
    const float size = 0.05f + 0.3f * test::uniform01(rng);
    const Vec3 v0 = c + test::uniform_sphere_direction(rng) * size, v1 = c + test::uniform_sphere_direction(rng) * size, v2 = c + test::uniform_sphere_direction(rng) * size;
    for (Vec3 v : {v0, v1, v2}) {
      indices.push_back(uint32_t(vertices.size()));
      vertices.push_back(v);
    }
    if (one_sided) one_sided->push_back({v0, v1, v2});
  }
  s.lights.push_back(std::make_unique<AreaLight>(vertices, indices, flat(3.0), false));
  vertices.clear();
  indices.clear();
  for (int k = 0; k < 50; ++k) {
    const Vec3 c = random_in_box(rng, {-5, 0, -5}, {5, 4, 5});
    for (int j = 0; j < 3; ++j) {
      indices.push_back(uint32_t(vertices.size()));
      vertices.push_back(c + test::uniform_sphere_direction(rng) * 0.2f);
    }
  }
  s.lights.push_back(std::make_unique<AreaLight>(vertices, indices, flat(0.5), true));
  for (int k = 0; k < 3; ++k)
    s.lights.push_back(std::make_unique<PointLight>(random_in_box(rng, {-5, 0, -5}, {5, 4, 5}), flat(0.1)));
  return s;
}

struct PartIndex {
  int light, part;
};

std::vector<PartIndex> all_parts(const TestScene& s) {
  std::vector<PartIndex> parts;
  for (size_t l = 0; l < s.lights.size(); ++l)
    for (int k = 0; k < s.lights[l]->part_count(); ++k) parts.push_back({int(l), k});
  return parts;
}

// Whether part `part` of `light` can contribute at `at` by its own bounds (the leaf's importance), or, for a light
// at infinity, has power.
bool part_scores(const Light& light, int part, const LightSamplingPoint& at) {
  if (light.is_infinite()) return light.total_power_w(1.0) > 0.0;
  const std::optional<LightBounds> b = light.part_bounds(part);
  return b && light_importance(*b, at.position_m, at.normal) > 0.0f;
}

// Chi-square of sample() against pmf() at one point, over every part plus "no light"; returns the p-value and
// checks every returned probability against pmf() bit for bit, and that a part has probability > 0 exactly where
// it scores > 0 (`*scoring`: how many parts do).
double chi_square_at(const BvhLightSampler& sampler, const TestScene& scene, const LightSamplingPoint& at, int draws,
                     std::mt19937& rng, double* probability_sum, int* scoring) {
  const std::vector<PartIndex> parts = all_parts(scene);
  std::vector<int> first(scene.lights.size());
  for (size_t i = 0, n = 0; i < scene.lights.size(); n += size_t(scene.lights[i]->part_count()), ++i) first[i] = int(n);
  std::vector<double> expected(parts.size() + 1), observed(parts.size() + 1, 0.0);
  double sum = 0.0;
  *scoring = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    const float p = sampler.pmf(at, parts[i].light, parts[i].part);
    REQUIRE(p >= 0.0f);
    const bool scores = part_scores(*scene.lights[size_t(parts[i].light)], parts[i].part, at);
    *scoring += scores ? 1 : 0;
    INFO("light " << parts[i].light << " part " << parts[i].part << ": pmf " << p);
    CHECK((p > 0.0f) == scores);
    sum += p;
    expected[i] = draws * double(p);
  }
  expected.back() = draws * std::fmax(0.0, 1.0 - sum);
  int mismatched = 0;
  for (int d = 0; d < draws; ++d) {
    const auto choice = sampler.sample(at, test::uniform01(rng));
    if (!choice) {
      observed.back() += 1;
      continue;
    }
    if (choice->probability != sampler.pmf(at, choice->light, choice->part)) ++mismatched;
    observed[size_t(first[size_t(choice->light)] + choice->part)] += 1;
  }
  CHECK(mismatched == 0);
  *probability_sum = sum;
  return test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one).p_value;
}

}  // namespace

TEST_CASE("light BVH: sampled frequencies equal pmf() at random points of three scenes") {
  std::mt19937 rng(2024);
  constexpr int kPoints = 30, kDraws = 20000;
  const int tests = 3 * kPoints;
  int nothing_scores = 0;
  const std::vector<std::pair<const char*, TestScene>> scenes = [] {
    std::vector<std::pair<const char*, TestScene>> v;
    v.emplace_back("room", room_scene());
    v.emplace_back("outdoor", outdoor_scene());
    v.emplace_back("1,050 triangles", many_scene());
    return v;
  }();
  for (const auto& [name, scene] : scenes) {
    const auto pointers = scene.pointers();
    // Unlimited searches (the default): Σ = 1 (the capped option is tested below).
    const BvhLightSampler sampler(pointers, BvhLightSampler::Importance::broadband, 0);
    for (int i = 0; i < kPoints; ++i) {
      // A quarter of the points have no normal (media, transmissive surfaces).
      const Vec3 p = random_in_box(rng, {-4, 0.05f, -4}, {4, 3.5f, 4});
      const LightSamplingPoint at{p, i % 4 == 0 ? Vec3{} : test::uniform_sphere_direction(rng)};
      double sum = 0.0;
      int scoring = 0;
      INFO(std::string(name) << " point " << i << " at (" << p.x << ", " << p.y << ", " << p.z << ")");
      const double p_value = chi_square_at(sampler, scene, at, kDraws, rng, &sum, &scoring);
      INFO("Σ pmf = " << sum << " over " << scoring << " parts that score > 0");
      CHECK(p_value > test::sidak_threshold(test::kChiSquareAlpha, tests));
      // Every light sample goes to a part that can contribute: Σ = 1 up to the rounding of products of ≤ 64 float
      // ratios (each within 2⁻²⁴ relative) summed over ≤ 1,053 parts in double.
      if (scoring > 0) {
        CHECK(sum == doctest::Approx(1.0).epsilon(64 * 0x1p-24));
      } else {
        ++nothing_scores;
        CHECK(sum == 0.0);
      }
    }
  }
  CHECK(nothing_scores < tests / 4);  // the test has points where something can contribute
}

TEST_CASE("light BVH, capped search: pmf() still equals the sampled frequency, the sum may fall short of 1") {
  // A capped search (8 visits, the cap kSearchBudget documents; an option, not the default, which is unlimited): at
  // points where a search gives up and the child it could not decide holds no
  // scoring leaf, a descent into it finds nothing (probability lost), but pmf() must still be exact and every part
  // that scores must keep probability > 0 (chi_square_at checks both).
  std::mt19937 rng(77);
  constexpr int kPoints = 40, kDraws = 20000;
  const TestScene scene = many_scene();
  const auto pointers = scene.pointers();
  constexpr int kCap = 8;
  static_assert(kCap != 0, "0 means unlimited: the test must cap");
  const BvhLightSampler capped(pointers, BvhLightSampler::Importance::broadband, kCap);
  double smallest = 1.0, mean = 0.0;
  int short_of_one = 0;
  for (int i = 0; i < kPoints; ++i) {
    const Vec3 p = random_in_box(rng, {-4, 0.05f, -4}, {4, 3.5f, 4});
    const LightSamplingPoint at{p, test::uniform_sphere_direction(rng)};
    double sum = 0.0;
    int scoring = 0;
    INFO("point " << i << " at (" << p.x << ", " << p.y << ", " << p.z << ")");
    const double p_value = chi_square_at(capped, scene, at, kDraws, rng, &sum, &scoring);
    CHECK(p_value > test::sidak_threshold(test::kChiSquareAlpha, kPoints));
    CHECK(sum <= 1.0 + 64 * 0x1p-24);
    if (scoring > 0) {
      smallest = std::min(smallest, sum);
      mean += sum / kPoints;
      short_of_one += sum < 1.0 - 64 * 0x1p-24;
    }
  }
  MESSAGE("capped search, 1,050 triangles, random normals: Σ pmf mean " << mean << ", smallest " << smallest
                                                                          << ", short of 1 at " << short_of_one
                                                                          << " of " << kPoints << " points");
  // A guard against the cap losing most of the probability, not a physical bound: measured 0.91 mean, 0.75
  // smallest at these points (all short of 1: half of these triangles face away from any given point).
  CHECK(mean > 0.8);
}

TEST_CASE("light BVH: the probabilities sum to 1 where every cluster can contribute") {
  // Point lights seen from points without a normal: every importance is positive, so no descent can fail.
  TestScene s;
  std::mt19937 rng(5);
  for (int k = 0; k < 300; ++k)
    s.lights.push_back(std::make_unique<PointLight>(random_in_box(rng, {-10, 0, -10}, {10, 5, 10}),
                                                    flat(0.01 + test::uniform01(rng))));
  s.lights.push_back(std::make_unique<EnvironmentLight>(flat(0.1)));
  const auto pointers = s.pointers();
  const BvhLightSampler sampler(pointers);
  for (int i = 0; i < 20; ++i) {
    const LightSamplingPoint at{random_in_box(rng, {-10, 0, -10}, {10, 5, 10}), Vec3{}};
    double sum = 0.0;
    for (size_t l = 0; l < s.lights.size(); ++l) sum += sampler.pmf(at, int(l), 0);
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-5));
    CHECK(sampler.pmf(at, 300, 0) == 0.5f);  // one environment: half, as the tree
  }
}

TEST_CASE("light BVH: lights of absurd brightness stay leaves that can be chosen, and the sums stay finite") {
  // Intensities far outside float's range (the scene format's `scale` has no bound) are squeezed into the tree's
  // range: every light with power stays a leaf and the bright ones do not overflow a node's sum. Found by the scene
  // fuzzer (a point light of scale 1e-50 had power but no leaf).
  const auto faint_pair = [] {
    TestScene s;
    s.lights.push_back(std::make_unique<PointLight>(Vec3{0, 1, 0}, flat(1e-50)));
    s.lights.push_back(std::make_unique<PointLight>(Vec3{0, 1e9f, 0}, flat(1e-30)));  // I/d² ≈ 5e-46: rounds to 0
    return s;
  };
  const LightSamplingPoint at{{0.5f, 0, 0}, {0, 1, 0}};
  SUBCASE("faint lights alone: both have probability > 0 (the importance floor)") {
    const TestScene s = faint_pair();
    const auto pointers = s.pointers();
    const BvhLightSampler sampler(pointers);
    CHECK(sampler.leaf_count() == 2);
    CHECK(sampler.pmf(at, 0, 0) > 0.0f);
    CHECK(sampler.pmf(at, 1, 0) > 0.0f);
    CHECK(sampler.pmf(at, 0, 0) + sampler.pmf(at, 1, 0) == doctest::Approx(1.0).epsilon(1e-6));
  }
  SUBCASE("beside lights 1e350 times brighter: still leaves, finite probabilities summing to 1") {
    // (their probabilities then round to 0 in float, as any probability below 1e-38 must)
    TestScene s = faint_pair();
    for (int k = 0; k < 4; ++k) s.lights.push_back(std::make_unique<PointLight>(Vec3{float(k), 2, 0}, flat(1e300)));
    const auto pointers = s.pointers();
    const BvhLightSampler sampler(pointers);
    CHECK(sampler.leaf_count() == 6);
    double sum = 0.0;
    for (size_t l = 0; l < s.lights.size(); ++l) {
      const float p = sampler.pmf(at, int(l), 0);
      CHECK(std::isfinite(p));
      sum += p;
    }
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-5));
  }
}

TEST_CASE("light BVH: nothing behind a one-sided emitter is ever chosen") {
  std::vector<Triangle> triangles;
  const TestScene scene = many_scene(&triangles);
  const auto pointers = scene.pointers();
  const BvhLightSampler sampler(pointers);
  std::mt19937 rng(11);
  int behind_checked = 0;
  for (int i = 0; i < 40; ++i) {
    const LightSamplingPoint at{random_in_box(rng, {-5, 0, -5}, {5, 4, 5}), i % 2 ? Vec3{} : test::uniform_sphere_direction(rng)};
    std::vector<bool> behind(triangles.size());
    for (size_t k = 0; k < triangles.size(); ++k) {
      const Triangle& t = triangles[k];
      const Vec3 n = cross(t.v1 - t.v0, t.v2 - t.v0);
      behind[k] = dot(at.position_m - t.v0, n) <= 0.0f;
      if (behind[k]) {
        ++behind_checked;
        REQUIRE(sampler.pmf(at, 0, int(k)) == 0.0f);
      }
    }
    for (int d = 0; d < 5000; ++d) {
      const auto choice = sampler.sample(at, test::uniform01(rng));
      if (choice && choice->light == 0) REQUIRE_FALSE(behind[size_t(choice->part)]);
    }
  }
  CHECK(behind_checked > 10000);  // about half of 40 × 1,000

  // Above the room's downward-facing ceiling light, it gets nothing, from any direction.
  const TestScene room = room_scene();
  const auto room_pointers = room.pointers();
  const BvhLightSampler room_sampler(room_pointers);
  for (int i = 0; i < 100; ++i) {
    const LightSamplingPoint at{random_in_box(rng, {-0.5f, 2.0f, -0.5f}, {0.5f, 3.0f, 0.5f}), test::uniform_sphere_direction(rng)};
    CHECK(room_sampler.pmf(at, 0, 0) == 0.0f);
    CHECK(room_sampler.pmf(at, 0, 1) == 0.0f);
  }
}

TEST_CASE("light BVH: spot and IES lights are never chosen outside their cones") {
  const TestScene scene = room_scene();
  const auto pointers = scene.pointers();
  const BvhLightSampler sampler(pointers);
  const SpotLight& spot = static_cast<const SpotLight&>(*scene.lights[2]);
  const Vec3 spot_position{-1.5f, 1.9f, 1}, ies_position{0, 1.9f, -1.5f};
  std::mt19937 rng(3);
  int inside = 0, outside = 0, ies_outside = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 w = test::uniform_sphere_direction(rng);
    const float distance = 0.2f + 3.0f * test::uniform01(rng);
    const LightSamplingPoint at{spot_position + w * distance, Vec3{}};
    const double angle_deg = std::acos(std::clamp(double(-w.y), -1.0, 1.0)) * 180.0 / 3.14159265358979;
    const float p = sampler.pmf(at, 2, 0);
    if (angle_deg > 30.5) {  // the outer half-angle is 30°; 0.5° of margin for float directions
      ++outside;
      CHECK(p == 0.0f);
      CHECK(spot.falloff(w) == 0.0f);
    } else if (angle_deg < 29.5) {
      ++inside;
      CHECK(p > 0.0f);
    }
    // The IES table is dark from γ = 90° on: nothing above its horizon.
    const LightSamplingPoint at_ies{ies_position + w * distance, Vec3{}};
    if (w.y > 0.02f) {
      ++ies_outside;
      CHECK(sampler.pmf(at_ies, 3, 0) == 0.0f);
    } else if (w.y < -0.02f) {
      CHECK(sampler.pmf(at_ies, 3, 0) > 0.0f);
    }
    for (int d = 0; d < 8; ++d) {
      const auto choice = sampler.sample(at, test::uniform01(rng));
      if (choice && choice->light == 2) CHECK(angle_deg <= 30.5);
    }
  }
  CHECK(inside > 100);
  CHECK(outside > 1000);
  CHECK(ies_outside > 1000);
}

TEST_CASE("light BVH: lights below an opaque surface's tangent plane are not chosen, without a normal they are") {
  TestScene s;
  s.lights.push_back(std::make_unique<PointLight>(Vec3{0, -1, 0}, flat(1.0)));
  s.lights.push_back(std::make_unique<PointLight>(Vec3{0, 1, 0}, flat(1.0)));
  const auto pointers = s.pointers();
  const BvhLightSampler sampler(pointers);
  const LightSamplingPoint up{{0.3f, 0, 0.2f}, {0, 1, 0}}, none{{0.3f, 0, 0.2f}, {}};
  CHECK(sampler.pmf(up, 0, 0) == 0.0f);
  CHECK(sampler.pmf(up, 1, 0) == 1.0f);
  CHECK(sampler.pmf(none, 0, 0) == doctest::Approx(0.5));
  CHECK(sampler.pmf(none, 1, 0) == doctest::Approx(0.5));
}

TEST_CASE("light BVH: an environment keeps the rule's share, a sun shares with the tree by irradiance") {
  // outdoor_scene: an environment (0), a spot 2 m up (1), a sun (2), a point light (3). Where the sun and the tree
  // can contribute, the environment gets the rule's 1/3 and the sun and the tree split the other 2/3 by the sun's
  // irradiance against the tree root's importance, each keeping at least kInfiniteRuleWeight of its 1/3.
  const float rule = BvhLightSampler::kInfiniteRuleWeight;
  const TestScene scene = outdoor_scene();
  const auto pointers = scene.pointers();
  const BvhLightSampler sampler(pointers);
  const auto tree_share = [&](const LightSamplingPoint& at) {
    return 1.0f - sampler.pmf(at, 0, 0) - sampler.pmf(at, 2, 0);
  };
  // Facing up, moving away from the lamps: the tree's share falls towards its floor, the sun's rises.
  float last = 1.0f;
  for (float x : {5.0f, 10.0f, 20.0f, 40.0f}) {
    const LightSamplingPoint at{{x, 0, 0.1f}, {0, 1, 0}};
    const float tree = tree_share(at);
    INFO("x = " << x << ": the tree's share " << tree << ", the sun's " << sampler.pmf(at, 2, 0));
    CHECK(sampler.pmf(at, 0, 0) == doctest::Approx(1.0 / 3.0).epsilon(1e-6));
    CHECK(tree < last);
    CHECK(tree >= (2.0f / 3.0f) * rule / 2.0f * (1.0f - 1e-5f));
    CHECK(sampler.pmf(at, 2, 0) >= (2.0f / 3.0f) * rule / 2.0f * (1.0f - 1e-5f));
    last = tree;
  }
  CHECK(last < (2.0f / 3.0f) * 0.2f);  // 40 m away the sun takes most of the 2/3
  // Next to the point light the tree gets more than twice its share 40 m away (the sun, E⊥ = 470 W/m², still
  // outshines the root's importance there), the sun still at least its floor.
  const LightSamplingPoint near{{3, 0.55f, 2}, {}};
  CHECK(tree_share(near) > 2.0f * last);
  CHECK(sampler.pmf(near, 2, 0) >= (2.0f / 3.0f) * rule / 2.0f * (1.0f - 1e-5f));
  // Above every finite light, facing up: the tree cannot contribute; the environment and the sun get half each.
  const LightSamplingPoint above{{0, 3, 0}, {0, 1, 0}};
  CHECK(sampler.pmf(above, 0, 0) == 0.5f);
  CHECK(sampler.pmf(above, 2, 0) == doctest::Approx(0.5));
  CHECK(sampler.pmf(above, 1, 0) == 0.0f);
  CHECK(sampler.pmf(above, 3, 0) == 0.0f);
  // The sun's measure is its irradiance at normal incidence, 1.0 W/(m²·nm) over 360-830 nm; the environment has none.
  CHECK(*scene.lights[2]->directional_irradiance_w_m2() == doctest::Approx(470.0).epsilon(1e-5));
  CHECK(!scene.lights[0]->directional_irradiance_w_m2().has_value());
}

TEST_CASE("light BVH: where the shares of the lights at infinity vary, pmf() equals the sampled frequency") {
  // Points from under the spot to 60 m away with normals in every direction, so the tree's share varies by more than
  // 2× (towards the rule's floor far away): chi-square over every part plus "no light", pmf() bit for bit the sampled
  // probability, Σ = 1 wherever something can contribute (chi_square_at: every part that scores has P > 0), and
  // the sun's probability > 0 wherever a direction drawn from its disc arrives above the surface.
  const TestScene scene = outdoor_scene();
  const auto pointers = scene.pointers();
  const BvhLightSampler sampler(pointers);
  std::mt19937 rng(31);
  constexpr int kPoints = 40, kDraws = 20000;
  float smallest_tree = 1.0f, largest_tree = 0.0f;
  const SampledWavelengths lambda(Float4(450.0f, 520.0f, 590.0f, 660.0f), Float4(1.0f / 470.0f));
  for (int i = 0; i < kPoints; ++i) {
    const float distance = 60.0f * float(i) / kPoints;
    const Vec3 p{distance * std::cos(float(i)), 0.05f + 0.5f * test::uniform01(rng), distance * std::sin(float(i))};
    const LightSamplingPoint at{p, i % 5 == 0 ? Vec3{} : test::uniform_sphere_direction(rng)};
    INFO("point " << i << " at (" << p.x << ", " << p.y << ", " << p.z << "), normal (" << at.normal.x << ", "
                  << at.normal.y << ", " << at.normal.z << ")");
    double sum = 0.0;
    int scoring = 0;
    const double p_value = chi_square_at(sampler, scene, at, kDraws, rng, &sum, &scoring);
    CHECK(p_value > test::sidak_threshold(test::kChiSquareAlpha, kPoints));
    if (scoring > 0) CHECK(sum == doctest::Approx(1.0).epsilon(64 * 0x1p-24));
    const float tree = 1.0f - sampler.pmf(at, 0, 0) - sampler.pmf(at, 2, 0);
    if (tree > 0.0f) smallest_tree = std::min(smallest_tree, tree);
    largest_tree = std::max(largest_tree, tree);
    bool sun_arrives = false;
    for (int d = 0; d < 64 && !sun_arrives; ++d) {
      const auto s = scene.lights[2]->sample_li(LightReference{p, Vec3{}}, lambda, {test::uniform01(rng), test::uniform01(rng)});
      sun_arrives = s && (at.normal == Vec3{} || dot(at.normal, s->wi) > 0.0f);
    }
    if (sun_arrives) CHECK(sampler.pmf(at, 2, 0) > 0.0f);
  }
  MESSAGE("the tree's share over the points where it can contribute: " << smallest_tree << " to " << largest_tree);
  CHECK(largest_tree > 2.0f * smallest_tree);  // the test covers points where the share varies
}

TEST_CASE("light BVH: build statistics of a 1,050-triangle scene") {
  const TestScene scene = many_scene();
  const auto pointers = scene.pointers();
  const BvhLightSampler sampler(pointers);
  CHECK(sampler.leaf_count() == 1053);
  CHECK(sampler.node_count() == 2 * 1053 - 1);
  CHECK(sampler.max_depth() < 40);
  CHECK(sampler.pmf({{0, 1, 0}, {}}, 5, 0) == 0.0f);  // no such light
  CHECK(sampler.pmf({{0, 1, 0}, {}}, 0, 1000) == 0.0f);  // no such part
}

namespace {

// A narrow triangular emission line of half-width 15 nm around `peak_nm` (relative units, scaled by `scale`).
LightSpectrum line(double peak_nm, double scale) {
  return LightSpectrum(std::make_shared<TabulatedSpectrum>(std::vector<double>{peak_nm - 15, peak_nm, peak_nm + 15},
                                                           std::vector<double>{0, 1, 0}, Extrapolation::zero, "line"),
                       scale);
}

// Coloured lights: red (630 nm) and blue (460 nm) point lights, a sodium-like line at 589 nm on a spot, a white
// ceiling quad, and 200 small triangles of an emissive mesh with a green line, under an environment.
TestScene coloured_scene() {
  TestScene s;
  s.lights.push_back(std::make_unique<PointLight>(Vec3{-1, 1.5f, 0}, line(630, 1.0)));
  s.lights.push_back(std::make_unique<PointLight>(Vec3{1, 1.5f, 0}, line(460, 1.0)));
  s.lights.push_back(std::make_unique<SpotLight>(Vec3{0, 2, -1}, Vec3{0, -1, 0.3f}, 30.0, 45.0, line(589, 0.5)));
  const std::vector<Vec3> quad = {{-0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, 0.5f}, {-0.5f, 2.5f, 0.5f}};
  const std::vector<uint32_t> down = {0, 1, 2, 0, 2, 3};
  s.lights.push_back(std::make_unique<AreaLight>(quad, down, flat(0.3), false));
  std::mt19937 rng(3);
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;
  for (int k = 0; k < 200; ++k) {
    const Vec3 c = random_in_box(rng, {-3, 0, -3}, {3, 3, 3});
    for (int j = 0; j < 3; ++j) {
      indices.push_back(uint32_t(vertices.size()));
      vertices.push_back(c + test::uniform_sphere_direction(rng) * 0.1f);
    }
  }
  s.lights.push_back(std::make_unique<AreaLight>(vertices, indices, line(530, 2.0), false));
  s.lights.push_back(std::make_unique<EnvironmentLight>(flat(0.01)));
  return s;
}

SampledWavelengths four_wavelengths(Float4 lambda_nm) { return SampledWavelengths(lambda_nm, Float4(1.0f / 470.0f)); }

}  // namespace

TEST_CASE("light BVH, spectral: sampled frequencies equal pmf() and sum to 1 at the path's wavelengths") {
  const TestScene scene = coloured_scene();
  const auto pointers = scene.pointers();
  const BvhLightSampler sampler(pointers, BvhLightSampler::Importance::spectral, 0);
  std::mt19937 rng(909);
  constexpr int kPoints = 30, kDraws = 20000;
  for (int i = 0; i < kPoints; ++i) {
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(test::uniform01(rng));
    const Vec3 p = random_in_box(rng, {-3, 0.05f, -3}, {3, 2.4f, 3});
    LightSamplingPoint at{p, i % 4 == 0 ? Vec3{} : test::uniform_sphere_direction(rng), &lambda};
    double sum = 0.0;
    int scoring = 0;
    INFO("point " << i << " at (" << p.x << ", " << p.y << ", " << p.z << "), hero " << lambda.hero_nm() << " nm");
    const double p_value = chi_square_at(sampler, scene, at, kDraws, rng, &sum, &scoring);
    CHECK(p_value > test::sidak_threshold(test::kChiSquareAlpha, kPoints));
    REQUIRE(scoring > 0);  // the environment always can
    CHECK(sum == doctest::Approx(1.0).epsilon(64 * 0x1p-24));
    // The same probabilities whichever lane is the hero (the lanes rotated), bit for bit: the per-lane light
    // densities of the spectral MIS are equal, as the integrators assume.
    const Float4 l = lambda.lambda_nm(), pdf = lambda.pdf();
    const SampledWavelengths rotated(Float4(l[2], l[3], l[0], l[1]), Float4(pdf[2], pdf[3], pdf[0], pdf[1]));
    LightSamplingPoint at_rotated = at;
    at_rotated.wavelengths = &rotated;
    int differing = 0;
    for (const PartIndex& part : all_parts(scene))
      differing += sampler.pmf(at, part.light, part.part) != sampler.pmf(at_rotated, part.light, part.part);
    CHECK(differing == 0);
  }
}

TEST_CASE("light BVH, spectral: the lights that emit at the path's wavelengths get the samples") {
  const TestScene scene = coloured_scene();
  const auto pointers = scene.pointers();
  const BvhLightSampler spectral(pointers, BvhLightSampler::Importance::spectral);
  const BvhLightSampler broadband(pointers);
  // Midway between the red and the blue light, no normal: the same geometry for both.
  const LightSamplingPoint at{{0, 1.5f, 0}, Vec3{}};
  const SampledWavelengths red = four_wavelengths(Float4(620, 625, 635, 640));
  const SampledWavelengths blue = four_wavelengths(Float4(450, 455, 465, 470));
  const SampledWavelengths infrared = four_wavelengths(Float4(800, 805, 810, 815));  // no light but the environment emits
  LightSamplingPoint at_red = at, at_blue = at, at_infrared = at;
  at_red.wavelengths = &red;
  at_blue.wavelengths = &blue;
  at_infrared.wavelengths = &infrared;
  const float red_bvh = broadband.pmf(at, 0, 0), blue_bvh = broadband.pmf(at, 1, 0);
  INFO("bvh: red " << red_bvh << ", blue " << blue_bvh);
  REQUIRE(red_bvh > 0.0f);
  REQUIRE(blue_bvh > 0.0f);
  // With all four lanes in the red light's band, the blue light keeps only the floor (1e-3 of its mean power)
  // against the red one's ~10 × its mean: their ratio falls by ~10⁴ against bvh's, and the reverse for blue lanes.
  CHECK(spectral.pmf(at_red, 1, 0) / spectral.pmf(at_red, 0, 0) < 1e-2f * blue_bvh / red_bvh);
  CHECK(spectral.pmf(at_blue, 0, 0) / spectral.pmf(at_blue, 1, 0) < 1e-2f * red_bvh / blue_bvh);
  CHECK(spectral.pmf(at_red, 0, 0) > red_bvh);
  CHECK(spectral.pmf(at_blue, 1, 0) > blue_bvh);
  // Where no finite light emits, each keeps a probability > 0 wherever bvh gives it one (the floor): the choice
  // stays unbiased.
  for (int light = 0; light < 4; ++light)
    CHECK((spectral.pmf(at_infrared, light, 0) > 0.0f) == (broadband.pmf(at, light, 0) > 0.0f));
  // Without wavelengths the spectral tree chooses as the broadband one.
  for (int light = 0; light < 4; ++light) CHECK(spectral.pmf(at, light, 0) == broadband.pmf(at, light, 0));
  CHECK(spectral.memory_bytes() >= broadband.memory_bytes() + size_t(spectral.node_count()) * 64);
}

namespace {

// A ceiling of downlights: 10 × 5 IES lights 1 cm below a ceiling at y = 3, their tables dark from γ = 90° on.
TestScene downlight_ceiling() {
  TestScene s;
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 5; ++k)
      s.lights.push_back(std::make_unique<GoniometricLight>(Vec3{-3.6f + 0.8f * float(i), 2.99f, -2.4f + 1.2f * float(k)},
                                                            Vec3{0, -1, 0}, Vec3{1, 0, 0}, flat(0.01 * (1 + k)),
                                                            downlight_table()));
  return s;
}

}  // namespace

TEST_CASE("light bounds: a cluster of downlights is culled behind their plane, where none of them emits") {
  // The table reaches γ = 90° and no further: each light emits only below its own horizontal plane, so the union of
  // two has importance 0 just above it (its bounding sphere reaches there, which alone would score > 0).
  const TestScene scene = downlight_ceiling();
  const LightBounds a = *scene.lights[0]->part_bounds(0), b = *scene.lights[7]->part_bounds(0);
  CHECK(a.half_space);
  const LightBounds both = unite(a, b);
  REQUIRE(both.half_space);
  const Vec3 on_ceiling{-3.2f, 3.0f, -1.8f}, below{-3.2f, 2.5f, -1.8f};
  for (const Vec3 normal : {Vec3{0, -1, 0}, Vec3{}}) {  // the ceiling's normal, or none
    CHECK(light_importance(both, on_ceiling, normal) == 0.0f);
    CHECK(light_importance(a, on_ceiling, normal) == 0.0f);
  }
  for (const Vec3 normal : {Vec3{0, 1, 0}, Vec3{}}) CHECK(light_importance(both, below, normal) > 0.0f);
}

TEST_CASE("light BVH: sampled frequencies equal pmf() under a ceiling of 50 downlights (searches capped at 8 visits)") {
  // Points in the room, on its walls and on the ceiling (where no downlight emits), with and without a normal: the
  // chi-square of sample() against pmf(), pmf() bit-identical to sample()'s probability, P > 0 exactly for the lights
  // whose own bounds score, and the probabilities summing to 1 wherever one does.
  const TestScene scene = downlight_ceiling();
  const auto pointers = scene.pointers();
  const BvhLightSampler sampler(pointers, BvhLightSampler::Importance::broadband, 8);
  std::mt19937 rng(50);
  constexpr int kPoints = 40, kDraws = 20000;
  int lit_points = 0;
  for (int i = 0; i < kPoints; ++i) {
    Vec3 p = random_in_box(rng, {-4, 0, -3}, {4, 3, 3});
    Vec3 normal = i % 4 == 0 ? Vec3{} : test::uniform_sphere_direction(rng);
    if (i % 5 == 1) {  // on the ceiling, facing down
      p.y = 3.0f;
      normal = {0, -1, 0};
    } else if (i % 5 == 2) {  // on a wall
      p.x = -4.0f;
      normal = {1, 0, 0};
    }
    double sum = 0.0;
    int scoring = 0;
    INFO("point " << i << " at (" << p.x << ", " << p.y << ", " << p.z << ")");
    const double p_value = chi_square_at(sampler, scene, {p, normal}, kDraws, rng, &sum, &scoring);
    CHECK(p_value > test::sidak_threshold(test::kChiSquareAlpha, kPoints));
    if (scoring > 0) {
      ++lit_points;
      CHECK(sum == doctest::Approx(1.0).epsilon(64 * 0x1p-24));
    } else {
      CHECK(sum == 0.0);
    }
    if (i % 5 == 1) CHECK(scoring == 0);
  }
  CHECK(lit_points > kPoints / 2);
}
