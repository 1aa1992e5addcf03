// The procedural noise cloud (transport/media/noise_cloud_medium.h, pbrt-v4's `cloud` medium): its density formula
// written out from the documentation, its range and height profile, and ratio tracking and free flights through a
// placed cloud against exp(−σ_t ∫ d) integrated numerically along the ray.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "transmittance_statistics.h"
#include "transport/media/medium.h"
#include "transport/media/noise_cloud_medium.h"
#include "transport/textures/perlin_noise.h"

namespace rimu {
namespace {

const SpectrumPtr kCloudSigmaA = std::make_shared<ConstantSpectrum>(0.05);
const SpectrumPtr kCloudSigmaS = std::make_shared<ConstantSpectrum>(1.95);

// The density of the header's formula without the displacement (wispiness 0), term by term.
double reference_density(Vec3 p, double density_scale, double frequency) {
  double sum = 0.0;
  for (int i = 0; i < 5; ++i)
    sum += std::pow(0.5, i + 1) * perlin_noise(p * float(frequency) * float(std::pow(1.99, i)));
  const double thinning = std::clamp((1.0 - p.y) * 4.5 * density_scale * sum, 0.0, 1.0);
  return std::clamp(thinning + 2.0 * std::max(0.0, 0.5 - p.y), 0.0, 1.0);
}

Transform placement() { return Transform::translate({-2, 1, 4}) * Transform::rotate(25.0f, {0, 1, 1}) * Transform::scale({2.0f, 3.0f, 1.5f}); }

}  // namespace

TEST_CASE("noise cloud: pbrt-v4's density formula, in [0, 1], solid below y = 0") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.5f, 1.5f);
  const NoiseCloudMedium plain(kCloudSigmaA, kCloudSigmaS, 0.0f, {2.0f, 0.0f, 5.0f}, {0, 0, 0}, {1, 1, 1});
  const NoiseCloudMedium wispy(kCloudSigmaA, kCloudSigmaS, 0.0f, {2.0f, 1.0f, 5.0f}, {0, 0, 0}, {1, 1, 1});
  int wispy_differs = 0, partial = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const float d = plain.density_in_medium(p);
    CAPTURE(p.x);
    CAPTURE(p.y);
    CAPTURE(p.z);
    // Float against double sums of five octaves (each ≤ 1), times ≤ 4.5·2·1.5: a few 1e-7 at most.
    CHECK(std::fabs(d - reference_density(p, 2.0, 5.0)) <= 2e-6);
    const float w = wispy.density_in_medium(p);
    CHECK((w >= 0.0f && w <= 1.0f));
    if (p.y <= 0.0f) CHECK(w == 1.0f);
    if (std::fabs(w - d) > 1e-3f) ++wispy_differs;
    if (d > 0.0f && d < 1.0f) ++partial;
    // Outside the box the medium is empty, whatever the formula gives there.
    const bool inside = p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1 && p.z >= 0 && p.z <= 1;
    if (!inside) CHECK(plain.density(p) == 0.0f);
  }
  CHECK(wispy_differs > 500);  // the displacement moves the field
  CHECK(partial > 200);        // and the cloud has structure between empty and solid
  CHECK_THROWS(NoiseCloudMedium(kCloudSigmaA, kCloudSigmaS, 0.0f, {1.0f, -1.0f, 5.0f}, {0, 0, 0}, {1, 1, 1}));
  CHECK_THROWS(NoiseCloudMedium(kCloudSigmaA, kCloudSigmaS, 0.0f, {}, {0, 0, 0}, {1, 0, 1}));
}

TEST_CASE("noise cloud: ratio tracking and free flights through a placed cloud give exp(-sigma_t * integral of d)") {
  const Transform world_from_medium = placement();
  const Medium medium(NoiseCloudMedium(kCloudSigmaA, kCloudSigmaS, 0.0f, {2.0f, 1.0f, 5.0f}, {0, 0, 0}, {1, 1, 1}, world_from_medium));
  const NoiseCloudMedium& cloud = *medium.noise_cloud();
  // A ray through the box's middle at a slant (medium space), from outside to outside.
  const Vec3 from = world_from_medium.point({-0.2f, 0.35f, 0.1f}), to = world_from_medium.point({1.2f, 0.6f, 0.9f});
  const Ray ray{from, normalize(to - from)};
  const float t_max = length(to - from);
  // ∫ d dt by the midpoint rule at 200,000 steps (the density is continuous and piecewise smooth).
  const int steps = 200000;
  double integral = 0.0;
  for (int i = 0; i < steps; ++i) integral += cloud.density(ray.origin + ray.direction * (t_max * float((i + 0.5) / steps)));
  integral *= t_max / steps;
  const double expected = std::exp(-2.0 * integral);  // σ_t = 0.05 + 1.95 per unit density
  CAPTURE(integral);
  CAPTURE(expected);
  REQUIRE(expected > 0.05);
  REQUIRE(expected < 0.9);
  const test::TransmittanceStatistics s = test::transmittance_statistics(medium, ray, t_max, 100000);
  CAPTURE(s.mean);
  CAPTURE(s.standard_error);
  CHECK(std::fabs(s.mean - expected) <= 4.5 * s.standard_error + 1e-6);
  // Free flights (grey coefficients: every lane alike) pass with the same probability.
  const SampledWavelengths lambda(Float4(450.0f, 520.0f, 600.0f, 680.0f), Float4(1.0f));
  IndependentSampler sampler(5);
  sampler.start_pixel_sample(0, 0, 0);
  const int flights = 100000;
  int passed = 0;
  for (int i = 0; i < flights; ++i) {
    SampledSpectrum throughput = Float4(1.0f);
    if (!sample_free_flight(medium, ray, t_max, lambda, DistanceSampling::spectral_mis, sampler, throughput).scattered)
      ++passed;
  }
  const double share = double(passed) / flights, binomial = std::sqrt(expected * (1.0 - expected) / flights);
  CAPTURE(share);
  CHECK(std::fabs(share - expected) <= 4.5 * binomial);
}

}  // namespace rimu
