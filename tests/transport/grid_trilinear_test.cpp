// The voxel-grid medium's trilinear lookup and its transform (transport/media/grid_medium.h): values between voxel centres,
// majorants that bound every interpolated value, and the ratio-tracking transmittance through a rotated, scaled
// grid against the closed-form integral of the trilinear density along the ray.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "transport/media/grid_medium.h"
#include "transport/media/medium.h"
#include "transmittance_statistics.h"

namespace rimu {
namespace {

// 3 × 2 × 2 voxels of size 1 in [0, 3] × [0, 2] × [0, 2], x fastest.
const std::vector<float> kDensity = {0.4f, 1.3f, 0.2f,  0.9f, 0.1f, 1.6f,   // z = 0: y = 0, y = 1
                                     1.1f, 0.3f, 0.7f,  0.5f, 1.8f, 0.6f};  // z = 1
float at(int x, int y, int z) {
  return x < 0 || y < 0 || z < 0 || x > 2 || y > 1 || z > 1 ? 0.0f : kDensity[size_t((z * 2 + y) * 3 + x)];
}

// pbrt-v4's SampledGrid lookup written out independently: weights (1 − f, f) per axis at the sample position x − ½.
double trilinear_reference(Vec3 p) {
  double sum = 0.0;
  const double s[3] = {p.x - 0.5, p.y - 0.5, p.z - 0.5};
  const int i[3] = {int(std::floor(s[0])), int(std::floor(s[1])), int(std::floor(s[2]))};
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int d[3] = {dx, dy, dz};
        double w = 1.0;
        for (int a = 0; a < 3; ++a) {
          const double f = s[a] - i[a];
          w *= d[a] ? f : 1.0 - f;
        }
        sum += w * at(i[0] + dx, i[1] + dy, i[2] + dz);
      }
  return sum;
}

const SpectrumPtr kSigmaA = std::make_shared<ConstantSpectrum>(0.3), kSigmaS = std::make_shared<ConstantSpectrum>(0.5);

Transform placement() {
  return Transform::translate({1, 2, 3}) * Transform::rotate(30.0f, {1, 1, 0}) * Transform::scale({0.5f, 2.0f, 1.5f});
}

GridMedium grid(GridInterpolation interpolation, std::optional<Transform> world_from_grid) {
  return GridMedium(3, 2, 2, kDensity, {0, 0, 0}, {3, 2, 2}, kSigmaA, kSigmaS, 0.0f, interpolation, world_from_grid);
}

}  // namespace

TEST_CASE("grid medium: trilinear lookup between voxel centres, 0 beyond the grid, through the medium's transform") {
  const GridMedium plain = grid(GridInterpolation::trilinear, std::nullopt);
  const GridMedium placed = grid(GridInterpolation::trilinear, placement());
  // At voxel centres the stored value; at the box's faces half of it (the outside neighbour counts 0).
  CHECK(plain.density({0.5f, 0.5f, 0.5f}) == doctest::Approx(0.4));
  CHECK(plain.density({2.5f, 1.5f, 1.5f}) == doctest::Approx(0.6));
  CHECK(plain.density({0.0f, 0.5f, 0.5f}) == doctest::Approx(0.2));
  CHECK(plain.density({-0.01f, 0.5f, 0.5f}) == 0.0f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> ux(0.0f, 3.0f), uyz(0.0f, 2.0f);
  for (int i = 0; i < 200; ++i) {
    const Vec3 p{ux(rng), uyz(rng), uyz(rng)};
    CAPTURE(p.x);
    CAPTURE(p.y);
    CAPTURE(p.z);
    CHECK(plain.density(p) == doctest::Approx(trilinear_reference(p)).epsilon(1e-5));
    CHECK(placed.density(placement().point(p)) == doctest::Approx(trilinear_reference(p)).epsilon(1e-4));
  }
  // Voxel lookup stays piecewise constant.
  CHECK(grid(GridInterpolation::voxel, std::nullopt).density({0.1f, 0.1f, 0.1f}) == 0.4f);
}

TEST_CASE("grid medium: every density along a ray is below its segment's majorant, whatever the block size") {
  // A 20³ grid with isolated spikes next to block borders (of 4-, 8- and 16-voxel blocks alike): trilinear lookup
  // spreads a spike one voxel into the neighbouring block, whose majorant must include it. The medium's σ_t per
  // unit density decides the block size (GridMedium::majorant_block): thin, few lookups, large blocks; dense, small.
  std::vector<float> d(20 * 20 * 20, 0.01f);
  for (int k : {7, 8, 15, 16}) d[size_t((k * 20 + k) * 20 + k)] = 5.0f;
  std::vector<int> blocks;
  for (double scale : {0.01, 1000.0})
    for (GridInterpolation interpolation : {GridInterpolation::trilinear, GridInterpolation::voxel}) {
      const GridMedium medium(20, 20, 20, d, {0, 0, 0}, {1, 1, 1}, std::make_shared<ConstantSpectrum>(0.3 * scale),
                              std::make_shared<ConstantSpectrum>(0.5 * scale), 0.0f, interpolation,
                              Transform::rotate(20.0f, {0, 0, 1}));
      CAPTURE(scale);
      CAPTURE(medium.majorant_block());
      CAPTURE(interpolation == GridInterpolation::voxel);
      blocks.push_back(medium.majorant_block());
      std::mt19937 rng(9);
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      int checked = 0, violations = 0;
      for (int r = 0; r < 400; ++r) {
        const Vec3 target = Transform::rotate(20.0f, {0, 0, 1}).point({u(rng), u(rng), u(rng)});
        const Vec3 from{u(rng) * 4 - 2, u(rng) * 4 - 2, -1.0f};
        const Ray ray{from, normalize(target - from)};
        medium.for_each_majorant_segment(ray, 10.0f, [&](float t0, float t1, float majorant, const Ray&) {
          // Voxel lookup: the segment's ends lie on block faces, where the DDA's t and the lookup's voxel may
          // disagree by a rounding (tracking never looks up exactly there); the interior points only.
          const int ends = interpolation == GridInterpolation::voxel ? 1 : 0;
          for (int k = ends; k <= 16 - ends; ++k) {
            const float t = t0 + (t1 - t0) * float(k) / 16.0f;
            ++checked;
            if (medium.density(ray.origin + ray.direction * t) > majorant * (1.0f + 1e-5f)) ++violations;
          }
          return true;
        });
      }
      CHECK(checked > 10000);
      CHECK(violations == 0);
    }
  // The thin medium takes the largest blocks, the dense one the smallest.
  CHECK(blocks == std::vector<int>{16, 16, 4, 4});
}

TEST_CASE("grid medium: majorant blocks follow the cost of tracking: 4 voxels in a dense cloud, 16 in thin fog") {
  // The procedural cloud on 64³ voxels of 2 cm: σ_t = 100 per metre at density 1 makes ~2 tentative collisions per
  // voxel where it is dense (the pbrt-v3 cloud scene's figure), 0.1 per metre 0.002.
  const std::vector<float> cloud = procedural_cloud_density(64, 3);
  const auto medium = [&](double sigma_t) {
    return GridMedium(64, 64, 64, cloud, {0, 0, 0}, {1.28f, 1.28f, 1.28f}, std::make_shared<ConstantSpectrum>(0.1 * sigma_t),
                      std::make_shared<ConstantSpectrum>(0.9 * sigma_t), 0.0f, GridInterpolation::trilinear, std::nullopt);
  };
  CHECK(medium(100.0).majorant_block() == 4);
  CHECK(medium(0.1).majorant_block() == 16);
  // Placed at 1/100 of the size, the dense cloud is as thin per voxel as the fog.
  const GridMedium small(64, 64, 64, cloud, {0, 0, 0}, {1.28f, 1.28f, 1.28f}, std::make_shared<ConstantSpectrum>(10.0),
                         std::make_shared<ConstantSpectrum>(90.0), 0.0f, GridInterpolation::trilinear,
                         Transform::scale({0.001f, 0.001f, 0.001f}));
  CHECK(small.majorant_block() == 16);
}

TEST_CASE("grid medium: ratio-tracking transmittance through a placed trilinear grid equals exp of the density integral") {
  // In grid space the ray runs along x at y = 1.2, z = 1.45. Trilinear weights in y (sample 0.7) are 0.3, 0.7 and
  // in z (sample 0.95) 0.05, 0.95, so the density along x is piecewise linear through c_i = Σ w_y w_z d(i, y, z) at
  // the voxel centres x = i + ½ and c_0/2, c_2/2 at the faces: ∫ d dx = 0.375 c_0 + (c_0 + c_1)/2 + (c_1 + c_2)/2 +
  // 0.375 c_2 exactly (trapezoids of linear pieces). A world metre along the ray is 1/L grid units, L = |M x̂|.
  double c[3];
  for (int i = 0; i < 3; ++i)
    c[i] = 0.3 * 0.05 * at(i, 0, 0) + 0.7 * 0.05 * at(i, 1, 0) + 0.3 * 0.95 * at(i, 0, 1) + 0.7 * 0.95 * at(i, 1, 1);
  const double integral_grid = 0.875 * c[0] + c[1] + 0.875 * c[2];
  const Transform world_from_grid = placement();
  const Vec3 axis_world = world_from_grid.vector({1, 0, 0});
  const double metres_per_grid_unit = length(axis_world);
  const double sigma_t = 0.8;
  const double expected = std::exp(-sigma_t * metres_per_grid_unit * integral_grid);
  // Voxel lookup on the same ray (voxels y = 1, z = 1) has a different integral: the test can tell them apart.
  const double voxel_expected = std::exp(-sigma_t * metres_per_grid_unit * (at(0, 1, 1) + at(1, 1, 1) + at(2, 1, 1)));

  const Medium medium(grid(GridInterpolation::trilinear, world_from_grid));
  const Ray ray{world_from_grid.point({-1.0f, 1.2f, 1.45f}), normalize(axis_world)};
  const test::TransmittanceStatistics s = test::transmittance_statistics(medium, ray, float(5.0 * metres_per_grid_unit), 200000);
  const double mean = s.mean, standard_error = s.standard_error;
  CAPTURE(mean);
  CAPTURE(expected);
  CAPTURE(standard_error);
  CAPTURE(voxel_expected);
  CHECK(std::fabs(mean - expected) <= 4.5 * standard_error + 1e-6);
  CHECK(std::fabs(voxel_expected - expected) > 20.0 * standard_error);
}

TEST_CASE("grid medium: ratio tracking's Russian roulette ends deep walks early and keeps the mean exp(-tau)") {
  // The voxel grid above, unplaced, with σ_t = 5.6 per unit density (σ_a 2.1, σ_s 3.5). Along x at y = 0.5,
  // z = 1.5 the voxels hold 1.1, 0.3, 0.7; the segment x in [−1, 1.5] crosses the first and half the second:
  // τ = 5.6 · (1.1 + 0.5 · 0.3) = 7.0, T = 9.1e-4, deep in the roulette's range (below 0.1).
  const SpectrumPtr sigma_a = std::make_shared<ConstantSpectrum>(2.1), sigma_s = std::make_shared<ConstantSpectrum>(3.5);
  const Medium medium(GridMedium(3, 2, 2, kDensity, {0, 0, 0}, {3, 2, 2}, sigma_a, sigma_s, 0.0f,
                                 GridInterpolation::voxel, std::nullopt));
  const Ray ray{{-1.0f, 0.5f, 1.5f}, {1.0f, 0.0f, 0.0f}};
  const double expected = std::exp(-5.6 * (1.1 + 0.5 * 0.3));
  const test::TransmittanceStatistics s = test::transmittance_statistics(medium, ray, 2.5f, 400000);
  CAPTURE(s.mean);
  CAPTURE(expected);
  CAPTURE(s.standard_error);
  CHECK(std::fabs(s.mean - expected) <= 4.5 * s.standard_error);
  CHECK(s.standard_error < 0.05 * expected);  // the check above means something
  // No voxel reaches its block's majorant (1.8) along this ray, so without the roulette no estimate is exactly 0;
  // with it, a walk that reaches T̂ < 0.1 survives with probability T̂/0.1, and most estimates are 0.
  const SampledWavelengths lambda(Float4(450.0f, 520.0f, 600.0f, 680.0f), Float4(1.0f));
  IndependentSampler sampler(3);
  sampler.start_pixel_sample(0, 0, 0);
  int zeros = 0;
  const int count = 20000;
  for (int i = 0; i < count; ++i) {
    SampledSpectrum throughput = Float4(1.0f);
    const SegmentTransmittance t =
        estimate_transmittance(medium, ray, 2.5f, lambda, DistanceSampling::spectral_mis, sampler, throughput);
    if (t.transmittance[0] == 0.0f) ++zeros;
  }
  CHECK(zeros > count / 2);
}

}  // namespace rimu
