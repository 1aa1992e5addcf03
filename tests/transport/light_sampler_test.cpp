// Picking lights by power: chi-square against the powers, zero-power lights, empty scenes, and the weights each
// light type reports.
#include <doctest/doctest.h>

#include <random>
#include <memory>
#include <numbers>
#include <vector>

#include "light_test_support.h"
#include "transport/lights/area_light.h"
#include "transport/lights/distant_light.h"
#include "transport/lights/power_light_sampler.h"
#include "transport/lights/point_light.h"

using namespace rimu;

TEST_CASE("light sampler picks lights in proportion to their power and never a dark one") {
  const std::vector<double> power_w = {10.0, 0.0, 2.5, 100.0, 0.0, 0.01};
  const PowerLightSampler sampler(power_w);
  CHECK(sampler.light_count() == 6);
  const int n = 100000;
  std::vector<double> observed(power_w.size(), 0.0), expected(power_w.size());
  double total = 0;
  for (double p : power_w) total += p;
  for (size_t i = 0; i < power_w.size(); ++i) {
    expected[i] = n * power_w[i] / total;
    CHECK(sampler.probability(int(i)) == doctest::Approx(power_w[i] / total).epsilon(1e-6));
  }
  std::mt19937 rng(40);
  for (int s = 0; s < n; ++s) {
    const auto pick = sampler.pick(test::uniform01(rng));
    REQUIRE(pick);
    REQUIRE(power_w[pick->index] > 0.0);
    REQUIRE(pick->probability == sampler.probability(pick->index));
    observed[pick->index] += 1;
  }
  CHECK(test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one).p_value > test::kChiSquareAlpha);
  CHECK(sampler.probability(-1) == 0.0f);
  CHECK(sampler.probability(6) == 0.0f);
}

TEST_CASE("light sampler of a scene without power picks nothing") {
  const std::vector<double> zeros = {0.0, 0.0};
  CHECK_FALSE(PowerLightSampler(zeros).pick(0.3f));
  CHECK_FALSE(PowerLightSampler(std::vector<double>{}).pick(0.3f));
  CHECK(PowerLightSampler(zeros).probability(0) == 0.0f);
}

TEST_CASE("light sampler weights lights by their radiant power, lights at infinity by the scene radius") {
  auto spectrum = std::make_shared<ConstantSpectrum>(1.0);
  const PointLight point({0, 0, 0}, LightSpectrum(spectrum, 1.0));      // 4π · 470 W
  const DistantLight sun({0, 0, 1}, LightSpectrum(spectrum, 4.0));      // π r² · 4 · 470 W
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<uint32_t> idx = {0, 1, 2};
  const AreaLight dark(v, idx, LightSpectrum(spectrum, 0.0), false);  // black: never picked
  const std::vector<const Light*> lights = {&point, &sun, &dark};
  const PowerLightSampler sampler(lights, 1.0);
  // With r = 1 m the sun's weight is 4π, equal to the point light's.
  CHECK(sampler.probability(0) == doctest::Approx(0.5));
  CHECK(sampler.probability(1) == doctest::Approx(0.5));
  CHECK(sampler.probability(2) == 0.0f);
}

TEST_CASE("power sampler chooses whole lights: part -1, and a mesh's pdf is that of the whole mesh") {
  auto spectrum = std::make_shared<ConstantSpectrum>(1.0);
  const PointLight point({0, 0, 0}, LightSpectrum(spectrum, 1.0 / (4.0 * std::numbers::pi)));  // 470 W
  // Two triangles of areas 0.5 and 2 m²: 470·2.5 W in all.
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 1}, {0, 2, 1}};
  const std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5};
  const AreaLight mesh(v, idx, LightSpectrum(spectrum, 1.0 / std::numbers::pi), false);
  const std::vector<const Light*> lights = {&point, &mesh};
  const PowerLightSampler sampler(lights, 1.0);
  CHECK_FALSE(sampler.chooses_parts());
  CHECK(sampler.part_of_hit(1) == -1);
  const LightSamplingPoint at{{0.2f, 0.2f, 3}, {}};
  CHECK(sampler.pmf(at, 0, -1) == doctest::Approx(1.0 / 3.5));
  CHECK(sampler.pmf(at, 1, -1) == doctest::Approx(2.5 / 3.5));
  CHECK(sampler.pmf(at, 1, 0) == 0.0f);
  std::mt19937 rng(9);
  std::vector<double> observed(2, 0.0);
  const int n = 60000;
  for (int s = 0; s < n; ++s) {
    const auto c = sampler.sample(at, test::uniform01(rng));
    REQUIRE(c);
    REQUIRE(c->part == -1);
    REQUIRE(c->probability == sampler.pmf(at, c->light, c->part));
    observed[size_t(c->light)] += 1;
  }
  const std::vector<double> expected = {n / 3.5, n * 2.5 / 3.5};
  CHECK(test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one).p_value > test::kChiSquareAlpha);
  // Part −1 samples the whole mesh: its density is the mesh's, d²/(A |cos θ|), not a triangle's.
  const LightReference ref{{0.2f, 0.2f, 3}, {}};
  const SampledWavelengths lambda(Float4(500.0f), Float4(1.0f));
  const auto whole = mesh.sample_part_li(-1, ref, lambda, {0.3f, 0.6f});
  const auto same = mesh.sample_li(ref, lambda, {0.3f, 0.6f});
  REQUIRE(whole);
  REQUIRE(same);
  CHECK(whole->pdf_solid_angle == same->pdf_solid_angle);
}
