// Total diffuse reflectance and transmittance of a chromatic slab under a collimated beam: the volumetric path
// tracer (every distance-sampling variant) against an independent analog Monte Carlo written here.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "media_test_scene.h"
#include "transport/bsdfs/fresnel.h"
#include "transport/sampling/sampler.h"

namespace rimu {
namespace {

struct SlabAnswer {
  double reflectance = 0, transmittance = 0, reflectance_se = 0, transmittance_se = 0;
};

// Analog photon transport (double precision, its own HG sampling): photons enter at z = thickness going −z, fly
// exponential distances, are absorbed with probability 1 − albedo at each collision, scatter by HG otherwise.
// Tallies photons leaving through the top (reflectance) and, after ≥ 1 scattering, the bottom (the diffuse
// transmittance; the unscattered beam is a delta the camera-side estimate cannot see). Index-matched boundaries.
SlabAnswer analog_slab(double sigma_t, double albedo, double g, double thickness, int photons, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long reflected = 0, transmitted = 0;
  for (int p = 0; p < photons; ++p) {
    double z = thickness, dx = 0, dy = 0, dz = -1;
    bool scattered = false;
    for (;;) {
      z += dz * (-std::log(1.0 - u(rng)) / sigma_t);
      if (z > thickness) {
        reflected += scattered;
        break;
      }
      if (z < 0) {
        transmitted += scattered;
        break;
      }
      if (u(rng) >= albedo) break;
      scattered = true;
      // HG: cos θ by inverting the CDF (Henyey & Greenstein 1941; Witt 1977, "Multiple scattering in reflection
      // nebulae I", ApJS 35, Eq. 15); φ uniform; rotate about the old direction.
      double mu;
      if (std::fabs(g) < 1e-6) {
        mu = 2 * u(rng) - 1;
      } else {
        const double s = (1 - g * g) / (1 - g + 2 * g * u(rng));
        mu = (1 + g * g - s * s) / (2 * g);
      }
      const double st = std::sqrt(std::max(0.0, 1 - mu * mu)), phi = 2 * std::numbers::pi * u(rng);
      // An orthonormal basis around (dx, dy, dz).
      double ax, ay, az;
      if (std::fabs(dz) < 0.9) ax = -dy, ay = dx, az = 0;  // (0,0,1) × d
      else ax = 0, ay = -dz, az = dy;                       // (1,0,0) × d
      const double an = std::sqrt(ax * ax + ay * ay + az * az);
      ax /= an, ay /= an, az /= an;
      const double bx = dy * az - dz * ay, by = dz * ax - dx * az, bz = dx * ay - dy * ax;
      const double c = std::cos(phi) * st, s2 = std::sin(phi) * st;
      const double nx = dx * mu + ax * c + bx * s2, ny = dy * mu + ay * c + by * s2, nz = dz * mu + az * c + bz * s2;
      const double n = std::sqrt(nx * nx + ny * ny + nz * nz);
      dx = nx / n, dy = ny / n, dz = nz / n;
    }
  }
  SlabAnswer a;
  a.reflectance = double(reflected) / photons;
  a.transmittance = double(transmitted) / photons;
  a.reflectance_se = std::sqrt(a.reflectance * (1 - a.reflectance) / photons);
  a.transmittance_se = std::sqrt(a.transmittance * (1 - a.transmittance) / photons);
  return a;
}

// The chromatic slab: 1 m thick, σ_t = 1, 2, 4, 0.5 /m and albedo 0.9, 0.5, 0.99, 0.7 in the four lanes.
const Float4 kSigmaT(1.0f, 2.0f, 4.0f, 0.5f);
const Float4 kAlbedo(0.9f, 0.5f, 0.99f, 0.7f);

// Reflectance (above) and transmittance (below) by the path tracer: camera rays with cosine-weighted directions
// looking at the slab, a distant light of irradiance 1 straight above. R = (1/E) ∫ L cos θ dω = π · E_cos[L].
// `fixed_lanes`: every sample has the same hero (rgb transport's lanes never rotate) instead of rotating it.
// `diffuse_entry_ior` > 0: smooth faces of that index that let light in diffusely, and a walk that does not count
// towards max_depth (a subsurface medium's).
void path_traced_slab(float g, const VolumetricIntegratorSettings& settings, int count, bool fixed_lanes,
                      test::LaneStatistics& r, test::LaneStatistics& t, float diffuse_entry_ior = 0.0f) {
  const test::SlabScene slab(
      1.0f,
      Medium(HomogeneousMedium(test::bands(kSigmaT * (Float4(1.0f) - kAlbedo)), test::bands(kSigmaT * kAlbedo), g), 0,
             diffuse_entry_ior == 0.0f),
      std::make_unique<DistantLight>(Vec3{0, 0, 1}, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 1.0)),
      diffuse_entry_ior, diffuse_entry_ior > 0.0f);
  const VolumetricPathIntegrator integrator(slab.scene, settings);
  IndependentSampler sampler(11);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float pi = std::numbers::pi_v<float>;
  r = test::lane_statistics(count, [&](int i) {
    sampler.start_pixel_sample(i, 1, 0);
    const Ray ray{{0, 0, 2}, test::cosine_direction({u(rng), u(rng)}, -1.0f)};
    return test::rotated_radiance(integrator, ray, sampler, fixed_lanes ? 0 : i) * Float4(pi);
  });
  t = test::lane_statistics(count, [&](int i) {
    sampler.start_pixel_sample(i, 2, 0);
    const Ray ray{{0, 0, -1}, test::cosine_direction({u(rng), u(rng)}, 1.0f)};
    return test::rotated_radiance(integrator, ray, sampler, fixed_lanes ? 0 : i) * Float4(pi);
  });
}

void compare_with_analog(float g) {
  SlabAnswer analog[4];
  for (int k = 0; k < 4; ++k) analog[k] = analog_slab(kSigmaT[k], kAlbedo[k], g, 1.0, 100000, 17 + k);
  struct Variant {
    std::string name;
    DistanceSampling distance;
    WavelengthMode wavelengths;
    bool fixed_lanes = false;
  };
  // (a) single wavelength, (b) hero + spectral MIS, (c) averaged σ_t, plus hero without MIS and spectral tracking;
  // and the other wavelength modes' own techniques (distance_sampling_for): independent mode (no spectral MIS at
  // all, so hero-only flights) and rgb mode (spectral tracking, densities of the hero broadcast), whose integrator
  // bookkeeping must be just as unbiased whatever the lanes carry; rgb with its lanes fixed, as it runs.
  const Variant variants[] = {{"single", DistanceSampling::spectral_mis, WavelengthMode::single},
                              {"hero+MIS", DistanceSampling::spectral_mis, WavelengthMode::hero},
                              {"averaged", DistanceSampling::averaged, WavelengthMode::hero},
                              {"hero only", DistanceSampling::hero_only, WavelengthMode::hero},
                              {"spectral tracking", DistanceSampling::spectral_tracking, WavelengthMode::hero},
                              {"independent mode", DistanceSampling::spectral_mis, WavelengthMode::independent},
                              {"rgb mode", DistanceSampling::spectral_mis, WavelengthMode::rgb, true}};
  for (const Variant& v : variants) {
    VolumetricIntegratorSettings s;
    s.distance = v.distance;
    s.path.wavelengths = v.wavelengths;
    s.path.max_depth = 64;
    test::LaneStatistics r, t;
    path_traced_slab(g, s, 4000, v.fixed_lanes, r, t);
    for (int k = 0; k < 4; ++k) {
      CAPTURE(v.name);
      CAPTURE(k);
      CAPTURE(analog[k].reflectance);
      CAPTURE(analog[k].transmittance);
      CHECK(r.non_finite + t.non_finite == 0);
      // Both are Monte Carlo estimates: their difference has standard error √(se₁² + se₂²); 5 of them bound a
      // correct pair's difference with probability 1 − 6e-7.
      CHECK(std::fabs(r.mean[k] - analog[k].reflectance) <=
            5.0 * std::hypot(r.standard_error[k], analog[k].reflectance_se));
      CHECK(std::fabs(t.mean[k] - analog[k].transmittance) <=
            5.0 * std::hypot(t.standard_error[k], analog[k].transmittance_se));
    }
  }
}

// The same slab behind smooth faces of index η that let light in diffusely (DielectricBsdf, "Diffuse entry"), lit
// straight from above, isotropic scattering, by analog photons: a share 1 − F(1) of the beam enters (F(1) is the
// mirror reflection, a delta the camera cannot see), each photon along μ = cos θ drawn ∝ (1 − F_int(μ)) μ (by
// rejection from the cosine); at a face a photon reflects with F_int(μ) (totally beyond the critical angle) and
// leaves otherwise, refracted, carrying its flux. Tallies what leaves the top (R) and the bottom (T).
SlabAnswer analog_diffuse_entry_slab(double sigma_t, double albedo, double eta, int photons, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto inside_reflectance = [&](double mu) { return fresnel_dielectric(-mu, eta); };
  long reflected = 0, transmitted = 0;
  for (int p = 0; p < photons; ++p) {
    double mu;
    do mu = std::sqrt(u(rng));
    while (u(rng) < inside_reflectance(mu));
    double z = 1.0, dz = -mu;  // only the depth matters in an infinite slab
    for (;;) {
      const double next = z + dz * (-std::log(1.0 - u(rng)) / sigma_t);
      if (next > 1.0 || next < 0.0) {
        z = next > 1.0 ? 1.0 : 0.0;
        if (u(rng) < inside_reflectance(std::fabs(dz))) {
          dz = -dz;
          continue;
        }
        (z == 1.0 ? reflected : transmitted) += 1;
        break;
      }
      z = next;
      if (u(rng) >= albedo) break;
      dz = 2 * u(rng) - 1;  // isotropic
    }
  }
  const double entered = 1.0 - fresnel_dielectric(1.0, eta);
  SlabAnswer a;
  const double r = double(reflected) / photons, t = double(transmitted) / photons;
  a.reflectance = entered * r;
  a.transmittance = entered * t;
  a.reflectance_se = entered * std::sqrt(r * (1 - r) / photons);
  a.transmittance_se = entered * std::sqrt(t * (1 - t) / photons);
  return a;
}

}  // namespace

TEST_CASE("Slab reflectance and transmittance, isotropic scattering, all distance-sampling variants agree with analog MC") {
  compare_with_analog(0.0f);
}

TEST_CASE("Slab reflectance and transmittance, HG g 0.7, all distance-sampling variants agree with analog MC") {
  compare_with_analog(0.7f);
}

TEST_CASE("Diffuse entry: a slab behind smooth water faces takes in a distant light and agrees with analog MC") {
  // A smooth refracting face stops shadow rays and no path hits a distant light, so without diffuse entry the
  // walk beneath never sees it (the first check); with it, next-event estimation at the faces lets it in.
  // Reflectance and transmittance against the analog photons above, hero + spectral MIS and single wavelength.
  constexpr float kWater = 1.33f;
  SlabAnswer analog[4];
  for (int k = 0; k < 4; ++k) analog[k] = analog_diffuse_entry_slab(kSigmaT[k], kAlbedo[k], kWater, 100000, 23 + k);
  {
    const test::SlabScene refracting(
        1.0f, Medium(HomogeneousMedium(test::bands(kSigmaT * (Float4(1.0f) - kAlbedo)), test::bands(kSigmaT * kAlbedo), 0.0f)),
        std::make_unique<DistantLight>(Vec3{0, 0, 1}, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 1.0)),
        kWater);
    const VolumetricPathIntegrator integrator(refracting.scene, VolumetricIntegratorSettings{});
    IndependentSampler sampler(3);
    const test::LaneStatistics dark = test::lane_statistics(500, [&](int i) {
      sampler.start_pixel_sample(i, 0, 0);
      return test::rotated_radiance(integrator, Ray{{0, 0, 2}, normalize(Vec3{0.3f, 0.1f, -1.0f})}, sampler, i);
    });
    for (int k = 0; k < 4; ++k) CHECK(dark.mean[k] == 0.0);
  }
  for (const WavelengthMode mode : {WavelengthMode::hero, WavelengthMode::single}) {
    VolumetricIntegratorSettings s;
    s.path.wavelengths = mode;
    s.path.max_depth = 64;
    test::LaneStatistics r, t;
    path_traced_slab(0.0f, s, 4000, false, r, t, kWater);
    for (int k = 0; k < 4; ++k) {
      CAPTURE(k);
      CAPTURE(int(mode));
      CAPTURE(r.mean[k]);
      CAPTURE(analog[k].reflectance);
      CAPTURE(t.mean[k]);
      CAPTURE(analog[k].transmittance);
      CHECK(r.non_finite + t.non_finite == 0);
      CHECK(std::fabs(r.mean[k] - analog[k].reflectance) <= 5.0 * std::hypot(r.standard_error[k], analog[k].reflectance_se));
      CHECK(std::fabs(t.mean[k] - analog[k].transmittance) <=
            5.0 * std::hypot(t.standard_error[k], analog[k].transmittance_se));
    }
  }
}

TEST_CASE("Diffuse entry: a white furnace stays uniform behind glass faces that let light in diffusely") {
  // A non-absorbing slab under uniform radiance 1 holds η² inside, which the faces' diffuse entry keeps (its
  // normalisation, DielectricBsdf): every direction outside sees exactly 1, from above, below and at grazing.
  const test::SlabScene slab(1.0f,
                             Medium(HomogeneousMedium(test::bands(Float4(0.0f)), test::bands(Float4(0.25f, 0.5f, 1.0f, 2.0f)),
                                                      0.0f),
                                    0, false),
                             std::make_unique<test::UniformSky>(1.0f), 1.5f, true);
  VolumetricIntegratorSettings s;
  s.path.max_depth = 64;
  const VolumetricPathIntegrator integrator(slab.scene, s);
  IndependentSampler sampler(29);
  for (const Vec3 direction : {Vec3{0, 0, -1}, normalize(Vec3{0.9f, 0, -0.2f}), normalize(Vec3{0.2f, 0.3f, 1.0f})}) {
    const Ray ray{{0, 0, direction.z < 0 ? 2.0f : -1.0f}, direction};
    const test::LaneStatistics furnace = test::lane_statistics(8000, [&](int i) {
      sampler.start_pixel_sample(i, 0, 0);
      return test::rotated_radiance(integrator, ray, sampler, i);
    });
    CHECK(furnace.non_finite == 0);
    for (int k = 0; k < 4; ++k) {
      CAPTURE(k);
      CAPTURE(furnace.mean[k]);
      CAPTURE(furnace.standard_error[k]);
      CHECK(std::fabs(furnace.mean[k] - 1.0) <= 5.0 * furnace.standard_error[k] + 1e-5);
    }
  }
}

TEST_CASE("Textured albedo: a subsurface medium scaled by a uniform texture equals the medium built for that albedo") {
  // Chiang's σ_t depends on the mean free path alone, so a textured surface albedo A only rescales σ_s, per path, where
  // it enters (TexturedAlbedo). A medium built for A₀ = 0.5 with a texture of A = (0.95, 0.7, 0.3, 0.05) must render
  // as the medium built for A itself: reflectance and transmittance of the slab (diffuse-entry water faces, a distant
  // light) per lane within 5 combined standard errors; and far from the untextured A₀ medium (the texture acts).
  const SpectrumPtr mfp = std::make_shared<ConstantSpectrum>(0.4);
  const SpectrumPtr albedo = test::bands(0.95f, 0.7f, 0.3f, 0.05f);
  const auto slab_estimates = [&](Medium medium, uint64_t seed) {
    const test::SlabScene slab(
        1.0f, std::move(medium),
        std::make_unique<DistantLight>(Vec3{0, 0, 1}, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 1.0)),
        1.33f, true);
    VolumetricIntegratorSettings s;
    s.path.max_depth = 64;
    const VolumetricPathIntegrator integrator(slab.scene, s);
    IndependentSampler sampler(seed);
    std::mt19937 rng{uint32_t(seed)};
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float pi = std::numbers::pi_v<float>;
    std::array<test::LaneStatistics, 2> rt;
    for (int side = 0; side < 2; ++side)
      rt[size_t(side)] = test::lane_statistics(6000, [&](int i) {
        sampler.start_pixel_sample(i, side, 0);
        const Ray ray{{0, 0, side == 0 ? 2.0f : -1.0f}, test::cosine_direction({u(rng), u(rng)}, side == 0 ? -1.0f : 1.0f)};
        return test::rotated_radiance(integrator, ray, sampler, i) * Float4(pi);
      });
    return rt;
  };
  const auto uncounted = [](HomogeneousMedium h) { return Medium(std::move(h), 0, false); };
  Medium textured = uncounted(chiang2016_medium(ConstantSpectrum(0.5), *mfp, 0.0f));
  textured.set_textured_albedo(
      std::make_shared<const TexturedAlbedo>(std::make_shared<ConstantSpectralTexture>(albedo), 0.5));
  const auto with_texture = slab_estimates(textured, 31);
  const auto direct = slab_estimates(uncounted(chiang2016_medium(*albedo, *mfp, 0.0f)), 37);
  const auto base = slab_estimates(uncounted(chiang2016_medium(ConstantSpectrum(0.5), *mfp, 0.0f)), 41);
  for (int side = 0; side < 2; ++side)
    for (int k = 0; k < 4; ++k) {
      CAPTURE(side);
      CAPTURE(k);
      const test::LaneStatistics &a = with_texture[size_t(side)], &b = direct[size_t(side)], &c = base[size_t(side)];
      CAPTURE(a.mean[k]);
      CAPTURE(b.mean[k]);
      CAPTURE(c.mean[k]);
      CHECK(a.non_finite == 0);
      const double se = std::hypot(a.standard_error[k], b.standard_error[k]);
      CHECK(std::fabs(a.mean[k] - b.mean[k]) <= 5.0 * se);
      // The check has the power to see a texture that did nothing: the untextured A₀ = 0.5 medium would fail it in
      // every lane (the nearest, A = 0.7, by about 8 standard errors).
      CHECK(std::fabs(c.mean[k] - b.mean[k]) > 5.0 * std::hypot(c.standard_error[k], b.standard_error[k]));
    }
}

}  // namespace rimu
