// The parallax-aware vMF mixture of path guiding (transport/guiding/vmf_mixture.h): a fitted mixture's density
// integrates to one and its samples follow it (chi-square), it concentrates where the light is, and its lobes are
// re-aimed from where they were learned to the vertex that samples them (parallax).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "light_test_support.h"
#include "square_chi_square.h"
#include "transport/guiding/vmf_mixture.h"
#include "transport/sampling/equal_area_square.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;

// Uniformly sampled directions from the origin weighted by radiance·4π (escaping rays: no parallax).
// The record a path vertex at `position` leaves when its ray goes along `direction` and meets its light `distance`
// further (∞: escaped) with luminance weight `weight`.
GuidingSample record(Vec3 position, Vec3 direction, float distance, float weight) {
  return {position, {equal_area_sphere_to_square(direction), weight}, 0, distance};
}

std::vector<GuidingSample> distant_light_samples(double (*radiance)(Vec3), int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<GuidingSample> samples;
  for (int i = 0; i < count; ++i) {
    const Vec3 d = test::uniform_sphere_direction(rng);
    samples.push_back(record({0, 0, 0}, d, INFINITY, float(radiance(d) * 4.0 * kPi)));
  }
  return samples;
}

double sun_and_sky(Vec3 d) { return 1.0 + (dot(d, normalize(Vec3{0.3f, 0.4f, 0.8f})) > 0.99 ? 500.0 : 0.0); }
double upper_cosine(Vec3 d) { return std::fmax(0.0, double(d.z)); }
double two_lamps(Vec3 d) {
  return (d.x > 0.97f ? 50.0 : 0.0) + (dot(d, normalize(Vec3{-1.0f, -1.0f, 0.2f})) > 0.99f ? 200.0 : 0.0);
}

}  // namespace

TEST_CASE("A fitted vMF mixture's density integrates to one and its samples follow it (chi-square)") {
  double (*fields[])(Vec3) = {sun_and_sky, upper_cosine, two_lamps};
  for (int f = 0; f < 3; ++f) {
    CAPTURE(f);
    const VmfMixture mixture = VmfMixture::fit(distant_light_samples(fields[f], 50000, uint32_t(3 + f)), {});
    REQUIRE(!mixture.empty());
    const VertexMixture at = mixture.at({0.3f, -0.2f, 0.1f});  // distances ∞: the same lobes anywhere
    std::mt19937 rng(uint32_t(40 + f));
    std::vector<double> values;
    for (int i = 0; i < 200000; ++i) values.push_back(double(at.pdf(test::uniform_sphere_direction(rng))) * 4.0 * kPi);
    const auto [mean, standard_error] = test::mean_and_standard_error(values);
    CHECK(std::fabs(mean - 1.0) <= 4.5 * standard_error);

    // Chi-square over 32² cells of the equal-area square; a cell's expected count integrates the pdf over 8² points.
    const int cells = 32, sub = 8, draws = 200000;
    std::vector<double> observed(size_t(cells * cells), 0.0);
    const std::vector<double> expected = test::square_expected_counts(
        [&](Vec2 p) { return double(at.pdf(equal_area_square_to_sphere(p))) * 4.0 * kPi; }, cells, sub, draws);
    for (int i = 0; i < draws; ++i) {
      const Vec3 d = at.sample(test::uniform01(rng), {test::uniform01(rng), test::uniform01(rng)});
      REQUIRE(std::fabs(length(d) - 1.0f) < 1e-4f);
      REQUIRE(at.pdf(d) > 0.0f);
      const Vec2 p = equal_area_sphere_to_square(d);
      observed[test::square_cell(p, cells)] += 1.0;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CHECK(chi.p_value > test::sidak_threshold(test::kChiSquareAlpha, 3));
  }
}

TEST_CASE("A vMF mixture concentrates on a sun: its density there is far above uniform") {
  const VmfMixture mixture = VmfMixture::fit(distant_light_samples(sun_and_sky, 50000, 8), {});
  // The 8° sun (0.49 % of the sphere) carries 500·0.0049/(500·0.0049 + 1) ≈ 71 % of the light.
  const VertexMixture at = mixture.at({0, 0, 0});
  CHECK(at.pdf(normalize(Vec3{0.3f, 0.4f, 0.8f})) * 4.0 * kPi > 30.0);
  CHECK(at.pdf(normalize(Vec3{-0.3f, -0.4f, -0.8f})) * 4.0 * kPi < 1.0);
}

TEST_CASE("Parallax: a lobe learned across a wide leaf is re-aimed at its light from the vertex that samples it") {
  // Vertices spread over a 2 m × 2 m ceiling-like patch (z = 0) see a small bright patch at (0, 0, −2.5) below them:
  // the learned directions differ by ~40° across the leaf. From any vertex the guide must point at the patch.
  const Vec3 light{0.0f, 0.0f, -2.5f};
  std::mt19937 rng(17);
  std::vector<GuidingSample> samples;
  for (int i = 0; i < 40000; ++i) {
    const Vec3 p{2.0f * test::uniform01(rng) - 1.0f, 2.0f * test::uniform01(rng) - 1.0f, 0.0f};
    const Vec3 d = test::uniform_sphere_direction(rng);
    // The ray reaches the light's plane; it counts if it lands within 0.15 m of the light.
    float weight = 0.0f, distance = INFINITY;
    if (d.z < 0.0f) {
      distance = -2.5f / d.z;
      const Vec3 q = p + d * distance;
      if (length(q - light) < 0.15f) weight = 100.0f;
    }
    samples.push_back(record(p, d, distance, weight));
  }
  const VmfMixture mixture = VmfMixture::fit(samples, {});
  REQUIRE(!mixture.empty());
  for (const Vec3 vertex : {Vec3{-0.9f, -0.9f, 0.0f}, Vec3{0.9f, 0.2f, 0.0f}, Vec3{0.0f, 0.0f, 0.0f}}) {
    CAPTURE(vertex.x);
    const Vec3 towards = normalize(light - vertex);
    const VertexMixture at = mixture.at(vertex);
    // The heaviest lobe points at the light within 3° (without re-aiming, the corners are ~20° off).
    int heaviest = 0;
    for (int k = 1; k < at.count; ++k)
      if (at.weight[size_t(k)] > at.weight[size_t(heaviest)]) heaviest = k;
    CHECK(dot(at.mean[size_t(heaviest)], towards) > std::cos(3.0 * kPi / 180.0));
    CHECK(at.pdf(towards) * 4.0 * kPi > 50.0);
  }
}

TEST_CASE("vMF hard cases: no light, extreme concentrations") {
  std::vector<GuidingSample> dark(100, record({0, 0, 0}, {0, 0, 1}, 1.0f, 0.0f));
  CHECK(VmfMixture::fit(dark, {}).empty());
  for (float kappa : {0.0f, 1e-7f, 1e-3f, 1.0f, 100.0f, 1e5f}) {
    CAPTURE(kappa);
    CHECK(std::isfinite(vmf_normalisation(kappa)));
    for (float u : {0.0f, 1e-9f, 0.5f, 0x1.fffffep-1f}) {
      const float c = sample_vmf_cosine(kappa, u);
      CHECK(c >= -1.0f);
      CHECK(c <= 1.0f);
    }
  }
}
