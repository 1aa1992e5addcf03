// Emissive media (transport/media/medium_emission.h): the light a medium emits along a path's segments
// (emitted_along), against closed forms lane by lane. An absorbing slab shows L_e (1 − e^{−τ}); inside a thick
// emissive medium that also scatters, radiative equilibrium makes the radiance L_e in every direction whatever the
// albedo (Kirchhoff), which checks that emission and the spectral-MIS free flights combine without bias.
#include <doctest/doctest.h>

#include <cmath>

#include "media_test_scene.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "transport/sampling/sampler.h"

namespace rimu {
namespace {

// Per lane (400, 500, 600, 700 nm): the emitted radiance, the slab's optical thickness over 1 m (σ_a), and, for the
// equilibrium checks, σ_a and σ_s of a medium thick enough that 0.5 m is ≥ 12 diffusion lengths in every lane.
const Float4 kLe(0.5f, 1.0f, 2.0f, 4.0f);
const Float4 kTau(0.25f, 0.5f, 1.0f, 2.0f);
const Float4 kThickSigmaA(10.0f, 5.0f, 20.0f, 8.0f), kThickSigmaS(30.0f, 45.0f, 10.0f, 20.0f);

std::shared_ptr<const MediumEmission> uniform_emission() {
  return std::make_shared<const MediumEmission>(test::bands(kLe), 1.0);
}

Medium emissive(Medium medium) {
  medium.set_emission(uniform_emission(), 0);
  return medium;
}

// A grid medium of density 1 over the slab z ∈ [0, 1] (wide in x and y): the homogeneous medium, tracked.
Medium grid_slab(Float4 sigma_a, Float4 sigma_s) {
  return Medium(GridMedium(1, 1, 1, {1.0f}, {-1e3f, -1e3f, 0.0f}, {1e3f, 1e3f, 1.0f}, test::bands(sigma_a),
                           test::bands(sigma_s), 0.0f));
}

// Normal incidence through the slab from outside.
const Ray kThrough{{0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}};

}  // namespace

TEST_CASE("emissive media: an absorbing slab shows L_e (1 - exp(-tau)) per lane, homogeneous exactly, grid within its error") {
  test::SlabScene homogeneous(1.0f, emissive(Medium(HomogeneousMedium(test::bands(kTau), test::bands(Float4(0.0f)), 0.0f))),
                              std::make_unique<test::UniformSky>(0.0f));
  const test::LaneStatistics exact = test::render_ray(homogeneous, {}, kThrough, 64, 1);
  test::SlabScene grid(1.0f, emissive(grid_slab(kTau, Float4(0.0f))), std::make_unique<test::UniformSky>(0.0f));
  const test::LaneStatistics tracked = test::render_ray(grid, {}, kThrough, 40000, 2);
  CHECK(exact.non_finite == 0);
  CHECK(tracked.non_finite == 0);
  for (int k = 0; k < 4; ++k) {
    const double expected = kLe[k] * -std::expm1(-double(kTau[k]));
    CAPTURE(k);
    CAPTURE(expected);
    // The analytic segment: no randomness, float rounding only.
    CHECK(exact.mean[k] == doctest::Approx(expected).epsilon(1e-5));
    CHECK(exact.standard_error[k] <= 1e-6 * expected);
    // The collision estimator with ratio tracking (and its roulette): unbiased, with an error that shrinks.
    CAPTURE(tracked.mean[k]);
    CHECK(std::fabs(tracked.mean[k] - expected) <= 4.5 * tracked.standard_error[k]);
    CHECK(tracked.standard_error[k] < 0.01 * expected);
  }
}

TEST_CASE("emissive media: inside a thick emitting, scattering medium the radiance is L_e in every lane (equilibrium)") {
  // The camera in the middle of the 1 m slab, looking along it and across it: σ_tr = sqrt(3 σ_a σ_t) ≥ 25/m in every
  // lane, so the boundary 0.5 m away changes the radiance by less than e^{−12}.
  const Ray along{{0.0f, 0.0f, 0.5f}, normalize(Vec3{1.0f, 0.3f, 0.05f})};
  const Ray across{{0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, 1.0f}};
  for (const bool use_grid : {false, true}) {
    CAPTURE(use_grid);
    test::SlabScene slab(1.0f,
                         emissive(use_grid ? grid_slab(kThickSigmaA, kThickSigmaS)
                                           : Medium(HomogeneousMedium(test::bands(kThickSigmaA),
                                                                      test::bands(kThickSigmaS), 0.0f))),
                         std::make_unique<test::UniformSky>(0.0f));
    slab.scene.camera_medium = 0;
    for (const Ray& ray : {along, across}) {
      const test::LaneStatistics s = test::render_ray(slab, {}, ray, 20000, use_grid ? 3 : 4);
      CHECK(s.non_finite == 0);
      for (int k = 0; k < 4; ++k) {
        CAPTURE(k);
        CAPTURE(s.mean[k]);
        CHECK(std::fabs(s.mean[k] - kLe[k]) <= 4.5 * s.standard_error[k]);
        CHECK(s.standard_error[k] < 0.02 * kLe[k]);
      }
    }
  }
}

TEST_CASE("emissive media: a temperature grid emits pbrt-v4's peak-normalised black body, nothing at or below 100 K") {
  // One voxel of "temperature" 1900 read as T = (1900 − 100) × 1.25 = 2250 K, peak scaled to 3.
  const SpectrumPtr none = std::make_shared<ConstantSpectrum>(0.0);
  const auto field = [&](float value) {
    return std::make_shared<const GridMedium>(1, 1, 1, std::vector<float>{value}, Vec3{0, 0, 0}, Vec3{1, 1, 1}, none,
                                              none, 0.0f);
  };
  const SampledWavelengths lambda = test::test_lambda();
  const MediumEmission hot(field(1900.0f), 100.0, 1.25, 3.0);
  CHECK_FALSE(hot.uniform());
  const Float4 le = hot.radiance_at({0.5f, 0.5f, 0.5f}, lambda);
  const double peak = planck_radiance_w_m2_sr_nm(2.897771955e6 / 2250.0, 2250.0);
  for (int k = 0; k < 4; ++k)
    CHECK(le[k] == doctest::Approx(3.0 * planck_radiance_w_m2_sr_nm(lambda.lambda_nm(k), 2250.0) / peak).epsilon(1e-5));
  // The peak-normalised shape is BlackbodySpectrum's peak_one scale (the scene format's {"blackbody": T}).
  const BlackbodySpectrum shape(2250.0, BlackbodySpectrum::Scale::peak_one);
  for (int k = 0; k < 4; ++k) CHECK(le[k] == doctest::Approx(3.0 * shape.value(lambda.lambda_nm(k))).epsilon(1e-5));
  // Cold (T = 100 K exactly), outside the grid (temperature 0 there) and a non-finite temperature: no emission.
  const MediumEmission cold(field(180.0f), 100.0, 1.25, 3.0);
  CHECK(max_lane(cold.radiance_at({0.5f, 0.5f, 0.5f}, lambda)) == 0.0f);
  CHECK(max_lane(hot.radiance_at({5.0f, 0.5f, 0.5f}, lambda)) == 0.0f);
}

TEST_CASE("emissive media: emission along a segment with sigma_a = 0 in some lanes, and a zero-length segment") {
  // Lanes without absorption emit nothing (σ_a L_e = 0) and stay finite (σ_t = 0 in lane 0: the d limit).
  const Medium medium = emissive(Medium(HomogeneousMedium(test::bands(0.0f, 0.5f, 0.0f, 1.0f),
                                                          test::bands(0.0f, 0.0f, 2.0f, 0.0f), 0.0f)));
  IndependentSampler sampler(5);
  sampler.start_pixel_sample(0, 0, 0);
  const Ray ray{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
  const Float4 e = emitted_along(medium, ray, 2.0f, test::test_lambda(), sampler);
  CHECK(e[0] == 0.0f);
  CHECK(e[1] == doctest::Approx(1.0 * -std::expm1(-1.0)).epsilon(1e-5));
  CHECK(e[2] == 0.0f);
  CHECK(e[3] == doctest::Approx(4.0 * -std::expm1(-2.0)).epsilon(1e-5));
  // Infinite and empty segments.
  const Float4 far = emitted_along(medium, ray, INFINITY, test::test_lambda(), sampler);
  CHECK(far[3] == doctest::Approx(4.0).epsilon(1e-5));
  CHECK(max_lane(emitted_along(medium, ray, 0.0f, test::test_lambda(), sampler)) == 0.0f);
  const Medium grid = emissive(grid_slab(Float4(0.0f, 0.5f, 0.0f, 1.0f), Float4(0.0f, 0.0f, 2.0f, 0.0f)));
  for (int i = 0; i < 100; ++i) {
    const Float4 g = emitted_along(grid, ray, 2.0f, test::test_lambda(), sampler);
    CHECK(g[0] == 0.0f);
    CHECK(g[2] == 0.0f);
    CHECK(std::isfinite(g[1]));
    CHECK(std::isfinite(g[3]));
  }
}

}  // namespace rimu
