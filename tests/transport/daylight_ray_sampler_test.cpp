// Daylight rays (transport/lights/daylight_ray_sampler.h): the points where they meet a floor are distributed as
// density() says (chi-square on a grid, density integrated by a midpoint rule) for a sun through a window portal,
// a sun through the disc that stands in when the scene has no portal, and a sky through a skylight; density() is 0
// where no aperture lets the light in, and the light is chosen by the light it brings through the apertures.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "light_test_support.h"
#include "spectral/spectra/spectrum.h"
#include "transport/lights/distant_light.h"
#include "transport/lights/environment_light.h"
#include "transport/lights/daylight_ray_sampler.h"

using namespace rimu;

namespace {

LightSpectrum sun_flat(double scale) { return LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), scale); }

const SampledWavelengths kSunLambda{Float4(450.0f, 520.0f, 580.0f, 650.0f), Float4(1.0f / 470.0f)};

// Rays from `sampler` meeting the floor y = 0, binned on `cells`² cells over [x0, x1] × [z0, z1], against the
// density integrated over each cell (sub × sub midpoints); Pearson's test at kChiSquareAlpha.
void check_floor_distribution(const DaylightRaySampler& sampler, float x0, float x1, float z0, float z1) {
  constexpr int cells = 12, sub = 24, samples = 120000;
  std::vector<double> observed(cells * cells, 0.0), expected(cells * cells, 0.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const float dx = (x1 - x0) / cells, dz = (z1 - z0) / cells;
  int outside = 0, failed = 0;
  Vec3 to_light{};
  for (int i = 0; i < samples; ++i) {
    const auto ray = sampler.sample(kSunLambda, u01(rng), {u01(rng), u01(rng)}, {u01(rng), u01(rng)});
    if (!ray || !(ray->to_light.y > 0.0f)) {
      ++failed;
      continue;
    }
    to_light = ray->to_light;
    const float t = ray->origin.y / ray->to_light.y;
    const Vec3 p = ray->origin - ray->to_light * t;
    const int cx = int(std::floor((p.x - x0) / dx)), cz = int(std::floor((p.z - z0) / dz));
    if (cx < 0 || cx >= cells || cz < 0 || cz >= cells) {
      ++outside;
      continue;
    }
    observed[size_t(cz * cells + cx)] += 1.0;
  }
  double total = 0.0;
  for (int cz = 0; cz < cells; ++cz)
    for (int cx = 0; cx < cells; ++cx) {
      double integral = 0.0;
      for (int j = 0; j < sub; ++j)
        for (int i = 0; i < sub; ++i) {
          const Vec3 y{x0 + (float(cx) + (float(i) + 0.5f) / sub) * dx, 0.0f, z0 + (float(cz) + (float(j) + 0.5f) / sub) * dz};
          integral += double(sampler.density(0, y, {0, 1, 0}, to_light, 1.0f));
        }
      integral *= double(dx) * double(dz) / double(sub * sub);
      expected[size_t(cz * cells + cx)] = integral * samples;
      total += integral;
    }
  INFO("density integrated over the grid " << total << ", samples outside it " << outside);
  CHECK(failed == 0);
  CHECK(outside == 0);
  CHECK(total == doctest::Approx(1.0).epsilon(0.01));  // the midpoint rule at the patch's edges
  const auto result = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  INFO("chi-square " << result.statistic << " on " << result.degrees_of_freedom << " degrees of freedom");
  CHECK(result.p_value > test::kChiSquareAlpha);
}

}  // namespace

TEST_CASE("sun rays through a window portal land on the floor as their density says") {
  std::vector<std::unique_ptr<Light>> lights;
  const Vec3 sun_direction = normalize(Vec3{0.55f, 0.62f, -0.25f});
  lights.push_back(std::make_unique<DistantLight>(sun_direction, sun_flat(1.0)));
  auto sky = std::make_unique<EnvironmentLight>(sun_flat(0.0));  // black: its portal is an aperture, not a source
  const auto window = PortalRectangle::from_corners({4, 0.8f, -1.5f}, {4, 0.8f, 1.5f}, {4, 2.4f, 1.5f}, {4, 2.4f, -1.5f});
  REQUIRE(window);
  sky->set_portals(PortalSet({*window}));
  lights.push_back(std::move(sky));
  const DaylightRaySampler sampler(lights, {0, 1.5f, 0}, 5.5f, {0, 1.5f, 0});
  REQUIRE(!sampler.empty());
  CHECK(sampler.uses_portals());
  // The window's corners cast along the sun onto the floor bound the patch.
  float x0 = 1e9f, x1 = -1e9f, z0 = 1e9f, z1 = -1e9f;
  for (const Vec3 c : {Vec3{4, 0.8f, -1.5f}, Vec3{4, 0.8f, 1.5f}, Vec3{4, 2.4f, 1.5f}, Vec3{4, 2.4f, -1.5f}}) {
    const Vec3 p = c - sun_direction * (c.y / sun_direction.y);
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z), z1 = std::max(z1, p.z);
  }
  check_floor_distribution(sampler, x0, x1, z0, z1);
  // No sun through the wall beside the window, nor for a light that is not a source (the sky).
  CHECK(sampler.density(0, {2.0f, 0.0f, 2.9f}, {0, 1, 0}, sun_direction, 1.0f) == 0.0f);
  CHECK(sampler.density(1, {x0 + 0.5f * (x1 - x0), 0.0f, z0 + 0.5f * (z1 - z0)}, {0, 1, 0}, sun_direction, 1.0f) == 0.0f);
}

TEST_CASE("sun rays without portals start on a disc around the scene and cover it") {
  std::vector<std::unique_ptr<Light>> lights;
  const Vec3 sun_direction = normalize(Vec3{-0.3f, 0.8f, 0.4f});
  lights.push_back(std::make_unique<DistantLight>(sun_direction, sun_flat(1.0)));
  const DaylightRaySampler sampler(lights, {0, 0, 0}, 2.0f, {0, 0, 0});
  REQUIRE(!sampler.empty());
  CHECK(!sampler.uses_portals());
  // The disc of radius 2 cast onto the floor: an ellipse within these bounds.
  const float half_x = 2.0f / sun_direction.y + 0.01f, half_z = 2.0f / sun_direction.y + 0.01f;
  const Vec3 centre_on_floor = Vec3{0, 0, 0};
  check_floor_distribution(sampler, centre_on_floor.x - half_x, centre_on_floor.x + half_x,
                           centre_on_floor.z - half_z, centre_on_floor.z + half_z);
}

TEST_CASE("sun rays choose among suns by the light they bring through the apertures") {
  // Two suns of equal irradiance, one square on to a 1 m² skylight and one at 60° from its normal: probabilities
  // 1/(1 + cos 60°) and cos 60°/(1 + cos 60°), seen in the density at a point both light.
  std::vector<std::unique_ptr<Light>> lights;
  const Vec3 overhead{0, 1, 0};
  const Vec3 slanted = normalize(Vec3{std::sqrt(3.0f), 1.0f, 0.0f});  // 60° from the vertical
  lights.push_back(std::make_unique<DistantLight>(overhead, sun_flat(1.0)));
  lights.push_back(std::make_unique<DistantLight>(slanted, sun_flat(1.0)));
  auto sky = std::make_unique<EnvironmentLight>(sun_flat(0.0));
  const auto skylight = PortalRectangle::from_corners({-0.5f, 3, -0.5f}, {0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, {-0.5f, 3, 0.5f});
  REQUIRE(skylight);
  sky->set_portals(PortalSet({*skylight}));
  lights.push_back(std::move(sky));
  const DaylightRaySampler sampler(lights, {0, 1.5f, 0}, 4.0f, {0, 1.5f, 0});
  // Densities at points right under the skylight's centre along each sun, on a floor facing up (|n·ω| = n·ω).
  const float p_overhead = sampler.density(0, {0, 0, 0}, {0, 1, 0}, overhead, 1.0f);
  const Vec3 under_slanted = Vec3{0, 3, 0} - slanted * (3.0f / slanted.y);
  const float p_slanted = sampler.density(1, under_slanted, {0, 1, 0}, slanted, 1.0f);
  // p = P_i |n·ω| / (A |n_portal·ω|) with A = 1 m²: the overhead sun P/1 · 1/1, the slanted P · (1/2)/(1/2).
  CHECK(p_overhead == doctest::Approx(1.0 / 1.5).epsilon(1e-4));
  CHECK(p_slanted == doctest::Approx(0.5 / 1.5).epsilon(1e-4));
}

namespace {

// A 1 m × 2 m skylight 3 m above the floor y = 0; only the sky is a source, `inside` tells the sampler which side
// is in. Expected per floor cell: the density integrated over directions through the skylight,
// ∫ p(y, ω) dω = ∫_portal p(y, ω(q)) |n_q·ω| / r² dA_q (a midpoint rule over the portal), over the cell (a midpoint
// rule); the rays drawn upwards (a fraction `up`) miss the floor.
void check_skylight_distribution(Vec3 inside, double up) {
  std::vector<std::unique_ptr<Light>> lights;
  auto sky = std::make_unique<EnvironmentLight>(sun_flat(1.0));
  const auto skylight = PortalRectangle::from_corners({-0.5f, 3, -1}, {0.5f, 3, -1}, {0.5f, 3, 1}, {-0.5f, 3, 1});
  REQUIRE(skylight);
  sky->set_portals(PortalSet({*skylight}));
  lights.push_back(std::move(sky));
  const DaylightRaySampler sampler(lights, {0, 1.5f, 0}, 4.0f, inside);
  REQUIRE(!sampler.empty());
  constexpr int cells = 10, sub = 4, portal_sub = 12, samples = 100000;
  constexpr float half = 5.0f, cell = 2.0f * half / cells;
  std::vector<double> observed(cells * cells + 2, 0.0), expected(cells * cells + 2, 0.0);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int i = 0; i < samples; ++i) {
    const auto ray = sampler.sample(kSunLambda, u01(rng), {u01(rng), u01(rng)}, {u01(rng), u01(rng)});
    if (!ray) continue;
    if (!(ray->to_light.y > 0.0f)) {  // travels up (−ω): leaves through the skylight
      observed[cells * cells + 1] += 1.0;
      continue;
    }
    const Vec3 p = ray->origin - ray->to_light * (ray->origin.y / ray->to_light.y);
    const int cx = int(std::floor((p.x + half) / cell)), cz = int(std::floor((p.z + half) / cell));
    observed[cx >= 0 && cx < cells && cz >= 0 && cz < cells ? size_t(cz * cells + cx) : size_t(cells * cells)] += 1.0;
  }
  double grid = 0.0;
  for (int cz = 0; cz < cells; ++cz)
    for (int cx = 0; cx < cells; ++cx) {
      double integral = 0.0;
      for (int j = 0; j < sub; ++j)
        for (int i = 0; i < sub; ++i) {
          const Vec3 y{-half + (float(cx) + (float(i) + 0.5f) / sub) * cell, 0.0f,
                       -half + (float(cz) + (float(j) + 0.5f) / sub) * cell};
          for (int b = 0; b < portal_sub; ++b)
            for (int a = 0; a < portal_sub; ++a) {
              const Vec3 q = skylight->corner + skylight->edge_a * ((float(a) + 0.5f) / portal_sub) +
                             skylight->edge_b * ((float(b) + 0.5f) / portal_sub);
              const Vec3 d = q - y;
              const float r2 = dot(d, d);
              const Vec3 w = d / std::sqrt(r2);
              integral += double(sampler.density(0, y, {0, 1, 0}, w, 0.0f)) * std::fabs(w.y) / r2 *
                          (skylight->area_m2() / (portal_sub * portal_sub));
            }
        }
      integral *= double(cell) * double(cell) / double(sub * sub);
      expected[size_t(cz * cells + cx)] = integral * samples;
      grid += integral;
    }
  expected[cells * cells] = (1.0 - up - grid) * samples;
  expected[cells * cells + 1] = up * samples;
  INFO("floor grid holds " << grid << " of the rays");
  CHECK(grid > 0.3);
  const auto result = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  INFO("chi-square " << result.statistic << " on " << result.degrees_of_freedom << " degrees of freedom");
  CHECK(result.p_value > test::kChiSquareAlpha);
}

}  // namespace

TEST_CASE("sky rays through a skylight go in and land on the floor as their density says") {
  check_skylight_distribution({0, 1.5f, 0}, 0.0);  // the camera below: every ray goes down
  check_skylight_distribution({2, 3, 0}, 0.5);     // a camera in the skylight's plane: either side, half go up
}
