// Environment portals: the spherical rectangle's solid angle against the closed form, its sampling against the
// exact solid angle of every cell (chi-square), a set of portals' pdf against its sampled frequencies and its
// integral over the sphere (also where two portals overlap), the corner checks, an environment light with a
// portal (irradiance through a window against the closed form, pdf_li consistent with sample_li, power π·A·∫L), and
// the light BVH holding such an environment as a leaf (pmf() against sampled frequencies, Σ = 1).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "light_test_support.h"
#include "spectral/spectra/spectrum.h"
#include "transport/lights/area_light.h"
#include "transport/lights/bvh_light_sampler.h"
#include "transport/lights/environment_light.h"
#include "transport/lights/environment_portal.h"
#include "transport/lights/point_light.h"
#include "test_support.h"

using namespace rimu;

namespace {
using rimu::test::kPi;
using rimu::test::kLambda;

/// Solid angle of the rectangle [x0, x1] × [y0, y1] in a plane at distance h from the point, coordinates measured
/// from the point's foot on the plane: the corner formula atan(xy / (h √(x² + y² + h²))) summed with signs.
double rectangle_solid_angle(double x0, double x1, double y0, double y1, double h) {
  const auto corner = [h](double x, double y) { return std::atan(x * y / (h * std::sqrt(x * x + y * y + h * h))); };
  return corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
}

// A 2 m × 1 m window in the plane x = 4 (edges along z and y), like the benchmark room's.
const PortalRectangle kWindow{{4, 1, -1}, {0, 0, 2}, {0, 1, 0}};
}  // namespace

TEST_CASE("portal corners: rectangles accepted in order, anything else refused") {
  const auto window = PortalRectangle::from_corners({4, 1, -1}, {4, 1, 1}, {4, 2, 1}, {4, 2, -1});
  REQUIRE(window);
  CHECK(window->area_m2() == doctest::Approx(2.0));
  CHECK(std::fabs(dot(window->normal(), Vec3{1, 0, 0})) == doctest::Approx(1.0));
  CHECK_FALSE(PortalRectangle::from_corners({0, 0, 0}, {1, 0, 0}, {1.5f, 1, 0}, {0.5f, 1, 0}));  // a parallelogram
  CHECK_FALSE(PortalRectangle::from_corners({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}));        // out of order
  CHECK_FALSE(PortalRectangle::from_corners({0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}));        // no area
  CHECK_FALSE(PortalRectangle::from_corners({0, 0, 0}, {1, 0, 0}, {1, 1, 0.1f}, {0, 1, 0}));     // not planar
}

TEST_CASE("spherical rectangle: solid angle equals the closed form, from either side and off axis") {
  // Points in front of, behind, just off and far from the window's plane.
  for (Vec3 origin : {Vec3{0, 1.5f, 0}, Vec3{-3.5f, 0.2f, 3.0f}, Vec3{3.99f, 2.5f, 0.3f}, Vec3{9, 1.2f, -6},
                      Vec3{-400, 1, 0}}) {
    CAPTURE(origin.x);
    CAPTURE(origin.y);
    CAPTURE(origin.z);
    const auto r = SphericalRectangle::make(kWindow, origin);
    REQUIRE(r);
    const double h = std::fabs(4.0 - origin.x);
    const double exact = rectangle_solid_angle(-1.0 - origin.z, 1.0 - origin.z, 1.0 - origin.y, 2.0 - origin.y, h);
    CHECK(r->solid_angle_sr() == doctest::Approx(exact).epsilon(1e-9));
  }
  CHECK_FALSE(SphericalRectangle::make(kWindow, {4, 0, 0}));  // in the window's plane: Ω = 0
}

TEST_CASE("spherical rectangle sampling is uniform in solid angle, by chi-square over cells of exact solid angle") {
  // Cells: a 12 × 8 grid on the window. Expected counts N Ω_cell / Ω, every Ω from the closed form; a sampler
  // uniform in area (or with a wrong Jacobian near the near edge) fails at these origins.
  for (Vec3 origin : {Vec3{3.2f, 0.3f, 1.8f}, Vec3{0, 1.5f, 0}, Vec3{6, 2.5f, -0.5f}}) {
    CAPTURE(origin.x);
    const auto r = SphericalRectangle::make(kWindow, origin);
    REQUIRE(r);
    const int nz = 12, ny = 8, n = 200000;
    const double h = std::fabs(4.0 - origin.x);
    std::vector<double> observed(nz * ny, 0.0), expected(nz * ny, 0.0);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nz; ++i) {
        const double z0 = -1.0 + 2.0 * i / nz, z1 = -1.0 + 2.0 * (i + 1) / nz;
        const double y0 = 1.0 + double(j) / ny, y1 = 1.0 + double(j + 1) / ny;
        expected[j * nz + i] = n * rectangle_solid_angle(z0 - origin.z, z1 - origin.z, y0 - origin.y, y1 - origin.y, h) /
                               r->solid_angle_sr();
      }
    std::mt19937 rng(7);
    for (int s = 0; s < n; ++s) {
      const Vec3 p = r->sample_point({test::uniform01(rng), test::uniform01(rng)});
      REQUIRE(std::fabs(p.x - 4.0f) < 1e-4f);
      const int i = std::clamp(int((p.z + 1.0f) / 2.0f * nz), 0, nz - 1), j = std::clamp(int((p.y - 1.0f) * ny), 0, ny - 1);
      observed[j * nz + i] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(chi.statistic);
    CHECK(chi.p_value > test::kChiSquareAlpha);
  }
}

TEST_CASE("portal set: sampled frequencies match pdf, and pdf integrates to 1 over the sphere") {
  // Two windows in different walls plus a skylight; then two portals that overlap as seen from the point (the
  // density doubles there: N/ΣΩ).
  const PortalRectangle side{{-1, 0.5f, 3}, {2, 0, 0}, {0, 1.5f, 0}};  // in the plane z = 3
  const PortalRectangle skylight{{-0.5f, 3, -0.5f}, {1, 0, 0}, {0, 0, 1}};
  const PortalRectangle behind_window{{6, 1.2f, -0.5f}, {0, 0, 2}, {0, 1, 0}};  // partly behind kWindow from the origin
  const Vec3 origin{0.5f, 1.2f, 0.2f};
  for (bool overlapping : {false, true}) {
    CAPTURE(overlapping);
    const PortalSet set = overlapping ? PortalSet({kWindow, behind_window}) : PortalSet({kWindow, side, skylight});
    // Chi-square over directions binned by the equal-area cells of a 48 × 24 (φ, cos θ) grid; expected counts
    // N ∫_cell pdf dω by 48 × 48 midpoints per cell. The midpoint rule errs by ~1/48 of a cell where a portal's
    // edge crosses it, so N is kept where that stays well inside the counts' own noise (~1,000 per lit cell).
    const int nphi = 48, nz = 24, sub = 48, n = 40000;
    std::vector<double> observed(nphi * nz, 0.0), expected(nphi * nz, 0.0);
    double integral = 0.0;
    for (int j = 0; j < nz; ++j)
      for (int i = 0; i < nphi; ++i) {
        double cell = 0.0;
        for (int b = 0; b < sub; ++b)
          for (int a = 0; a < sub; ++a) {
            const double phi = 2 * kPi * (i + (a + 0.5) / sub) / nphi, z = -1.0 + 2.0 * (j + (b + 0.5) / sub) / nz;
            const double rho = std::sqrt(std::max(0.0, 1 - z * z));
            cell += set.pdf(origin, Vec3{float(rho * std::cos(phi)), float(rho * std::sin(phi)), float(z)});
          }
        cell *= 4 * kPi / (double(nphi) * nz * sub * sub);
        expected[j * nphi + i] = n * cell;
        integral += cell;
      }
    // The midpoint rule misses edge cells' boundaries by O(1/sub); the integral is 1 to that accuracy.
    CHECK(integral == doctest::Approx(1.0).epsilon(3e-3));
    std::mt19937 rng(11);
    for (int s = 0; s < n; ++s) {
      const auto d = set.sample(origin, {test::uniform01(rng), test::uniform01(rng)});
      REQUIRE(d);
      REQUIRE(d->pdf_sr == set.pdf(origin, d->wi));
      double phi = std::atan2(double(d->wi.y), double(d->wi.x));
      if (phi < 0) phi += 2 * kPi;
      const int i = std::min(nphi - 1, int(phi / (2 * kPi) * nphi));
      const int j = std::clamp(int((d->wi.z + 1.0) / 2.0 * nz), 0, nz - 1);
      observed[j * nphi + i] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CAPTURE(chi.statistic);
    CHECK(chi.p_value > test::kChiSquareAlpha);
    // The same integral by uniform sphere sampling: E[4π pdf] = 1, within 5 standard errors.
    test::MeanEstimate e;
    for (int s = 0; s < 400000; ++s) e.add(4 * kPi * set.pdf(origin, test::uniform_sphere_direction(rng)));
    CAPTURE(e.mean());
    CHECK(std::fabs(e.mean() - 1.0) <= test::kMonteCarloSigmas * e.standard_error());
  }
}

TEST_CASE("environment light with a portal: irradiance through a window, pdf_li, power") {
  // A constant sky L through the window, received at a point facing it: E = L ∫_window cos θ dω. Closed form for a
  // rectangle parallel to the receiving surface, receiver on a corner's normal: the configuration factor
  // F = (1/2π)[X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))], X = a/c, Y = b/c, E = π L F (Howell's
  // catalogue, factor C-11); the point here sits on the normal through the corner (4, 1, -1).
  EnvironmentLight sky(LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 2.0));
  sky.set_portals(PortalSet({kWindow}));
  const double c = 3.0, X = 2.0 / c, Y = 1.0 / c;
  const double F = (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                    Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
                   (2 * kPi);
  const double exact = kPi * 2.0 * F;
  const LightReference ref{{1, 1, -1}, {1, 0, 0}};
  std::mt19937 rng(5);
  test::MeanEstimate e;
  for (int s = 0; s < 100000; ++s) {
    const auto ls = sky.sample_li(ref, kLambda, {test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(ls);
    REQUIRE(ls->pdf_solid_angle == sky.pdf_li(ref, ls->wi));
    REQUIRE(ls->wi.x > 0.0f);
    e.add(ls->radiance[1] * std::max(0.0f, dot(ls->wi, ref.normal)) / ls->pdf_solid_angle);
  }
  CAPTURE(e.mean());
  CAPTURE(exact);
  CHECK(std::fabs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error());
  // Directions that miss the window: density 0, radiance still the sky's (BSDF sampling counts them in full).
  CHECK(sky.pdf_li(ref, {0, 1, 0}) == 0.0f);
  CHECK(sky.radiance_escaped({0, 1, 0}, kLambda)[1] == doctest::Approx(2.0f));
  // Power through the window: π A ∫L dλ = π · 2 m² · 2 · 470 nm.
  CHECK(sky.total_power_w(100.0) == doctest::Approx(kPi * 2.0 * 2.0 * 470.0).epsilon(1e-6));
}

TEST_CASE("light BVH with a portal environment: the sky is a leaf, pmf() equals the sampled frequency, Σ = 1") {
  // A room: a one-sided ceiling panel facing down and a point light; the sky through kWindow (x = 4). The sky is
  // chosen by the tree like a two-sided area light on the window: more often near the window than far from it.
  std::vector<std::unique_ptr<Light>> lights;
  const std::vector<Vec3> quad = {{-0.5f, 2.9f, -0.5f}, {0.5f, 2.9f, -0.5f}, {0.5f, 2.9f, 0.5f}, {-0.5f, 2.9f, 0.5f}};
  lights.push_back(std::make_unique<AreaLight>(quad, std::vector<uint32_t>{0, 1, 2, 0, 2, 3},
                                               LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 5.0), false));
  lights.push_back(std::make_unique<PointLight>(Vec3{-3, 2, 3}, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 0.5)));
  auto sky = std::make_unique<EnvironmentLight>(LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 1.0));
  sky->set_portals(PortalSet({kWindow}));
  lights.push_back(std::move(sky));
  std::vector<const Light*> pointers;
  for (const auto& l : lights) pointers.push_back(l.get());
  const BvhLightSampler sampler(pointers);
  CHECK(sampler.leaf_count() == 4);  // the panel's two triangles, the point light and the sky
  std::mt19937 rng(99);
  constexpr int kPoints = 20, kDraws = 20000;
  for (int i = 0; i < kPoints; ++i) {
    const Vec3 p{-3.9f + 7.8f * test::uniform01(rng), 0.05f + 2.8f * test::uniform01(rng), -3.9f + 7.8f * test::uniform01(rng)};
    const Vec3 n = i % 3 == 0 ? Vec3{} : normalize(Vec3{2 * test::uniform01(rng) - 1, 2 * test::uniform01(rng) - 1, 2 * test::uniform01(rng) - 1});
    const LightSamplingPoint at{p, n};
    // Parts: panel triangles 0, 1; point light; sky; "none".
    const std::vector<std::pair<int, int>> parts = {{0, 0}, {0, 1}, {1, 0}, {2, 0}};
    std::vector<double> expected, observed(parts.size() + 1, 0.0);
    double sum = 0.0;
    for (auto [light, part] : parts) {
      const float pmf = sampler.pmf(at, light, part);
      sum += pmf;
      expected.push_back(kDraws * double(pmf));
    }
    expected.push_back(kDraws * std::max(0.0, 1.0 - sum));
    INFO("point " << i << " (" << p.x << ", " << p.y << ", " << p.z << "), Σ pmf " << sum);
    if (sum > 0.0) CHECK(sum == doctest::Approx(1.0).epsilon(1e-5));
    // Where the window is wholly above the tangent plane and in front of it, the sky can be chosen.
    if (n == Vec3{}) CHECK(sampler.pmf(at, 2, 0) > 0.0f);
    for (int d = 0; d < kDraws; ++d) {
      const auto choice = sampler.sample(at, test::uniform01(rng));
      if (!choice) {
        observed.back() += 1;
        continue;
      }
      REQUIRE(choice->probability == sampler.pmf(at, choice->light, choice->part));
      const auto it = std::find(parts.begin(), parts.end(), std::pair<int, int>{choice->light, choice->part});
      REQUIRE(it != parts.end());
      observed[size_t(it - parts.begin())] += 1;
    }
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CHECK(chi.p_value > test::sidak_threshold(test::kChiSquareAlpha, kPoints));
  }
  // Nearer the window, a larger share for the sky (normals facing it at both points).
  const LightSamplingPoint near_window{{3.5f, 1.5f, 0}, {0, 0, 0}}, far_side{{-3.5f, 1.5f, 0}, {0, 0, 0}};
  CHECK(sampler.pmf(near_window, 2, 0) > 2.0f * sampler.pmf(far_side, 2, 0));
}
