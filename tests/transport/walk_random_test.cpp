// The medium walks' own random numbers (transport/sampling/walk_random.h): a walk takes a fixed number of sampler
// dimensions however many tentative collisions it makes, and its stream is a deterministic, uniform function of
// the sampler's number and the ray.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "transport/media/grid_medium.h"
#include "transport/media/medium.h"
#include "transport/media/spectral_distance_sampling.h"
#include "transport/sampling/walk_random.h"
#include "counting_sampler.h"

namespace rimu {
namespace {

;

// A 4³ voxel grid over the unit cube: density 0.1 everywhere but one corner voxel of 1.0, off the rays below, with
// σ_t = 60 per unit density (σ_s 54, σ_a 6). The majorant is 60 per unit length across the cube while σ_t = 6 along
// the rays: ~60 tentative collisions per unit of length, 9 % of them real, so a walk makes ~11 before it scatters,
// and the old tracker's two sampler numbers per collision would show.
Medium sparse_in_majorant_grid() {
  std::vector<float> density(64, 0.1f);
  density[63] = 1.0f;
  return Medium(GridMedium(4, 4, 4, density, {0, 0, 0}, {1, 1, 1}, std::make_shared<ConstantSpectrum>(6.0),
                           std::make_shared<ConstantSpectrum>(54.0), 0.0f, GridInterpolation::voxel, std::nullopt));
}

}  // namespace

TEST_CASE("medium walks take one sampler dimension each, however many tentative collisions they make") {
  const Medium medium = sparse_in_majorant_grid();
  const SampledWavelengths lambda(Float4(450.0f, 520.0f, 600.0f, 680.0f), Float4(1.0f));
  const Ray ray{{-0.5f, 0.4f, 0.4f}, {1.0f, 0.0f, 0.0f}};
  test::CountingSampler sampler(11);
  sampler.start_pixel_sample(0, 0, 0);
  int scattered = 0;
  float deepest = 0.0f;
  for (int i = 0; i < 2000; ++i) {
    SampledSpectrum throughput = Float4(1.0f);
    const long before = sampler.count;
    const FreeFlight flight =
        sample_free_flight(medium, ray, 2.0f, lambda, DistanceSampling::spectral_mis, sampler, throughput);
    CHECK(sampler.count - before == 1);
    if (flight.scattered) {
      ++scattered;
      deepest = std::fmax(deepest, flight.t - 0.5f);  // the ray enters the cube at t = 0.5
    }
  }
  // Most flights scatter (they pass the cube with e^{-6}) and their events spread through it (beyond 0.55 with
  // probability e^{-3.3} each): the walks were long.
  CHECK(scattered > 1900);
  CHECK(deepest > 0.55f);

  // Shadow rays: one dimension through the sampler, none with a stream of their own (a walk crosses the cube in
  // ~60 tentative collisions, or ends by Russian roulette after some 20).
  for (int i = 0; i < 500; ++i) {
    SampledSpectrum throughput = Float4(1.0f);
    const long before = sampler.count;
    estimate_transmittance(medium, ray, 2.0f, lambda, DistanceSampling::spectral_mis, sampler, throughput);
    CHECK(sampler.count - before == 1);
    WalkRandom random(sampler.next_1d(), ray, 2.0f);
    const long after_key = sampler.count;
    estimate_transmittance(medium, ray, 2.0f, lambda, DistanceSampling::spectral_mis, &random, throughput);
    CHECK(sampler.count == after_key);
  }
}

TEST_CASE("walk streams: the same key gives the same numbers, neighbouring keys unrelated ones, all uniform") {
  const Ray ray{{0.25f, -1.0f, 3.0f}, {0.0f, 0.6f, 0.8f}};
  WalkRandom a(0.5f, ray, 2.0f), b(0.5f, ray, 2.0f);
  for (int i = 0; i < 100; ++i) CHECK(a.next_1d() == b.next_1d());

  // Keys one ulp apart in u, in the origin and in t_max: Pearson correlation of 10⁵ pairs within 5/√n of 0.
  const int n = 100000;
  const auto correlation = [n](WalkRandom x, WalkRandom y) {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (int i = 0; i < n; ++i) {
      const double u = x.next_1d(), v = y.next_1d();
      sx += u, sy += v, sxx += u * u, syy += v * v, sxy += u * v;
    }
    const double cov = sxy / n - sx / n * sy / n;
    return cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
  };
  Ray moved = ray;
  moved.origin.x = std::nextafter(ray.origin.x, 1.0f);
  const double bound = 5.0 / std::sqrt(double(n));
  CHECK(std::fabs(correlation(WalkRandom(0.5f, ray, 2.0f), WalkRandom(std::nextafter(0.5f, 1.0f), ray, 2.0f))) < bound);
  CHECK(std::fabs(correlation(WalkRandom(0.5f, ray, 2.0f), WalkRandom(0.5f, moved, 2.0f))) < bound);
  CHECK(std::fabs(correlation(WalkRandom(0.5f, ray, 2.0f), WalkRandom(0.5f, ray, std::nextafter(2.0f, 3.0f)))) < bound);

  // Uniformity: 64 bins over 2¹⁸ numbers; chi-square with 63 degrees of freedom exceeds 120 with probability ~1e-5.
  WalkRandom c(0.125f, ray, 1.0f);
  std::vector<int> bins(64, 0);
  const int draws = 1 << 18;
  for (int i = 0; i < draws; ++i) {
    const float u = c.next_1d();
    REQUIRE(u >= 0.0f);
    REQUIRE(u < 1.0f);
    ++bins[size_t(u * 64.0f)];
  }
  double chi2 = 0.0;
  const double expected = draws / 64.0;
  for (int count : bins) chi2 += (count - expected) * (count - expected) / expected;
  CAPTURE(chi2);
  CHECK(chi2 < 120.0);
}

}  // namespace rimu
