// The hair BSDF (Chiang et al. 2016): white furnace, exact attenuation per lane, sample() against pdf() by
// chi-square, pdf normalisation, the reciprocity that holds, finiteness at the extremes, and the frame contract
// with a curve hit (fibre direction from ∂p/∂u, h from v).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "bsdf_chi_square.h"
#include "spectral/error.h"
#include "spectral/spectra/spectrum.h"
#include "statistics.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/bsdfs/material.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;

HairParameters parameters(float beta_m, float beta_n, float alpha_deg = 2.0f) {
  HairParameters p;
  p.beta_m = beta_m;
  p.beta_n = beta_n;
  p.alpha_deg = alpha_deg;
  return p;
}

// A unit direction from its fibre-frame sin θ and azimuth φ, in a local frame where the fibre runs along +x.
Vec3 fibre_direction(float sin_theta, float phi) {
  const float c = std::sqrt(std::fmax(0.0f, 1.0f - sin_theta * sin_theta));
  return {sin_theta, c * std::cos(phi), c * std::sin(phi)};
}

struct SphereIntegral {
  std::array<double, 4> mean{}, standard_error{};
};

// ∫ g(wi) dωi over the sphere, per lane, by jittered stratified sampling of (cos θ, φ) in the local frame (area
// 4π): `replicates` independent estimates of `strata`² points each, whose spread gives the standard error.
template <typename G>
SphereIntegral integrate_sphere(const G& g, uint32_t seed, int strata = 160, int replicates = 8) {
  std::mt19937 rng(seed);
  std::vector<std::vector<double>> estimates(4);
  for (int r = 0; r < replicates; ++r) {
    std::array<double, 4> sum{};
    for (int i = 0; i < strata; ++i)
      for (int j = 0; j < strata; ++j) {
        const float z = -1.0f + 2.0f * (float(i) + test::uniform01(rng)) / float(strata);
        const float phi = float(2.0 * kPi) * (float(j) + test::uniform01(rng)) / float(strata);
        const float s = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
        const Float4 value = g(Vec3{s * std::cos(phi), s * std::sin(phi), z});
        for (int k = 0; k < 4; ++k) sum[size_t(k)] += value[k];
      }
    for (int k = 0; k < 4; ++k) estimates[size_t(k)].push_back(4.0 * kPi * sum[size_t(k)] / double(strata * strata));
  }
  SphereIntegral out;
  for (int k = 0; k < 4; ++k) {
    const auto [mean, error] = test::mean_and_standard_error(estimates[size_t(k)]);
    out.mean[size_t(k)] = mean;
    out.standard_error[size_t(k)] = error;
  }
  return out;
}

// The fibre at an angle to the frame's axes, so that the fibre-frame conversion is exercised.
const Vec2 kTiltedFibre{0.6f, 0.8f};

// wo for a fibre along kTiltedFibre, from its fibre-frame angles.
Vec3 tilted_wo(float sin_theta, float phi) {
  const Vec3 f = fibre_direction(sin_theta, phi);
  return {kTiltedFibre.x * f.x - kTiltedFibre.y * f.y, kTiltedFibre.y * f.x + kTiltedFibre.x * f.y, f.z};
}

}  // namespace

TEST_CASE("hair: the white furnace (σa = 0) scatters exactly all the light, for any wo, h and roughness") {
  // ∫ f |cos θi| dωi = Σ_p Ap = 1 (Fresnel's R, T and the geometric series of internal reflections). Tolerance:
  // 4 standard errors of the stratified estimate, plus 1e-5 for float rounding.
  uint32_t seed = 1;
  struct Incidence {
    float h, sin_o, phi_o;
  };
  for (const auto& [bm, bn] : {std::pair{0.3f, 0.3f}, {0.15f, 0.8f}, {0.8f, 0.15f}, {1.0f, 1.0f}})
    for (const auto& [h, sin_o, phi_o] : {Incidence{-0.9f, 0.0f, 1.2f}, {0.0f, 0.6f, -0.4f}, {0.5f, -0.95f, 2.8f}, {0.99f, 0.3f, 0.0f}}) {
      CAPTURE(bm);
      CAPTURE(bn);
      CAPTURE(h);
      CAPTURE(sin_o);
      const HairBsdf bsdf(kTiltedFibre, h, Float4(0.0f), parameters(bm, bn));
      const Vec3 wo = tilted_wo(sin_o, phi_o);
      const auto furnace = integrate_sphere([&](Vec3 wi) { return bsdf.eval(wo, wi) * Float4(std::fabs(wi.z)); }, seed++);
      CAPTURE(furnace.mean[0]);
      CAPTURE(furnace.standard_error[0]);
      CHECK(std::fabs(furnace.mean[0] - 1.0) < 4.0 * furnace.standard_error[0] + 1e-5);
      // The tolerance stays within a few parts per thousand (the narrowest azimuthal lobe, β_n = 0.15, is the
      // noisiest): a lobe normalisation off by 1 % would fail.
      CHECK(furnace.standard_error[0] < 5e-3);
    }
}

TEST_CASE("hair: with absorption the furnace is Σ Ap per lane, below 1 and falling with σa") {
  // Lane k has its own σa: the geometry is shared, the attenuation is not.
  const Float4 sigma_a(0.0f, 0.3f, 1.0f, 4.0f);
  uint32_t seed = 100;
  for (const float h : {-0.6f, 0.2f})
    for (const auto& [sin_o, phi_o] : {std::pair{0.3f, 0.5f}, {-0.7f, -2.0f}}) {
      const HairBsdf bsdf(kTiltedFibre, h, sigma_a, parameters(0.3f, 0.3f));
      const Vec3 wo = tilted_wo(sin_o, phi_o);
      const auto ap = bsdf.attenuation(wo);
      const Float4 expected = ap[0] + ap[1] + ap[2] + ap[3];
      const auto furnace = integrate_sphere([&](Vec3 wi) { return bsdf.eval(wo, wi) * Float4(std::fabs(wi.z)); }, seed++);
      CAPTURE(h);
      CAPTURE(sin_o);
      CHECK(expected[0] == doctest::Approx(1.0).epsilon(1e-6));
      for (int k = 0; k < 4; ++k) {
        CAPTURE(k);
        CAPTURE(furnace.mean[size_t(k)]);
        CAPTURE(expected[k]);
        CHECK(std::fabs(furnace.mean[size_t(k)] - expected[k]) < 4.0 * furnace.standard_error[size_t(k)] + 1e-5);
        if (k > 0) CHECK(expected[k] < expected[k - 1]);
      }
      // Absorption takes TT and TRT, not R: the most absorbing lane keeps at least the surface reflection.
      CHECK(expected[3] > ap[0][3]);
    }
}

TEST_CASE("hair: pdf() integrates to 1 in every lane, and sample() returns eval() and pdf() of its direction") {
  const Float4 sigma_a(0.1f, 0.0f, 2.0f, 8.0f);
  uint32_t seed = 200;
  std::mt19937 rng(7);
  for (const auto& [bm, bn] : {std::pair{0.3f, 0.3f}, {0.1f, 0.6f}, {0.9f, 0.9f}})
    for (const float h : {-1.0f, 0.3f}) {
      const HairBsdf bsdf(kTiltedFibre, h, sigma_a, parameters(bm, bn));
      const Vec3 wo = tilted_wo(0.4f, 0.9f);
      const auto total = integrate_sphere([&](Vec3 wi) { return bsdf.pdf(wo, wi); }, seed++);
      CAPTURE(bm);
      CAPTURE(h);
      for (int k = 0; k < 4; ++k) {
        CAPTURE(k);
        CAPTURE(total.mean[size_t(k)]);
        CHECK(std::fabs(total.mean[size_t(k)] - 1.0) < 4.0 * total.standard_error[size_t(k)] + 1e-5);
      }
      for (int i = 0; i < 2000; ++i) {
        const auto s = bsdf.sample(wo, test::uniform01(rng), {test::uniform01(rng), test::uniform01(rng)});
        REQUIRE(s);
        const Float4 f = bsdf.eval(wo, s->wi), pdf = bsdf.pdf(wo, s->wi);
        for (int k = 0; k < 4; ++k) {
          CHECK(s->f[k] == doctest::Approx(f[k]).epsilon(1e-5));
          CHECK(s->pdf[k] == doctest::Approx(pdf[k]).epsilon(1e-5));
        }
        // The weight f·|cos|/pdf is Σ Ap·MpNp / Σ P_p·MpNp: 1 for the hero when σa = 0 would make P = A; with
        // σa > 0 it is ΣAp (of the hero) exactly, since P_p = A_p/ΣA.
        const auto ap = bsdf.attenuation(wo);
        CHECK(s->hero_weight()[0] == doctest::Approx((ap[0] + ap[1] + ap[2] + ap[3])[0]).epsilon(1e-4));
      }
    }
}

TEST_CASE("chi-square: hair samples the density it reports") {
  struct Case {
    float beta_m, beta_n, h, sin_o, phi_o;
  };
  const Case cases[] = {{0.3f, 0.3f, 0.0f, 0.2f, 0.5f},   {0.3f, 0.3f, -0.7f, -0.6f, 2.0f}, {0.15f, 0.5f, 0.5f, 0.8f, -1.0f},
                        {0.7f, 0.15f, 0.9f, 0.0f, 1.57f}, {1.0f, 1.0f, -0.3f, 0.5f, 0.0f},  {0.2f, 0.2f, 0.4f, -0.3f, -2.5f}};
  const double threshold = test::sidak_threshold(0.01, int(std::size(cases)));
  uint64_t seed = 40;
  for (const Case& c : cases) {
    CAPTURE(c.beta_m);
    CAPTURE(c.beta_n);
    CAPTURE(c.h);
    CAPTURE(c.sin_o);
    const Bsdf bsdf = HairBsdf(kTiltedFibre, c.h, Float4(0.5f, 0.0f, 1.0f, 3.0f), parameters(c.beta_m, c.beta_n));
    const auto outcome = test::bsdf_chi_square(bsdf, tilted_wo(c.sin_o, c.phi_o), 50000, seed++);
    CAPTURE(outcome.failure);
    CAPTURE(outcome.chi_square);
    CHECK(outcome.failure.empty());
    CHECK(outcome.p_value > threshold);
  }
}

TEST_CASE("hair: reciprocal where the model's wo-only terms allow it, not with the cuticle tilt") {
  // The fibre's scattering function is S = Σ Mp Ap Np = f·|cos θi| (f carries pbrt's division by the ribbon's
  // cosine wi.z, which is not symmetric, so S is what reciprocity concerns). Ap and the exit azimuths depend on θo
  // and γo alone, so S(wo, wi) = S(wi, wo) only when swapping leaves them unchanged: α = 0 (no tilt), h = 0
  // (γo = 0, Φ = pπ is symmetric in φ) and |sin θi| = |sin θo|. The fibre runs along +x here, so local and fibre
  // coordinates coincide.
  const Vec2 along_x{1.0f, 0.0f};
  for (const float beta : {0.2f, 0.5f}) {
    const HairBsdf straight(along_x, 0.0f, Float4(0.0f, 0.4f, 1.5f, 5.0f), parameters(beta, beta, 0.0f));
    for (const float sin_o : {0.1f, 0.5f, -0.8f})
      for (const float sign : {1.0f, -1.0f})
        for (const auto& [phi_o, phi_i] : {std::pair{0.3f, 2.0f}, {-1.0f, 1.2f}, {2.5f, -2.9f}}) {
          const Vec3 wo = fibre_direction(sin_o, phi_o), wi = fibre_direction(sign * sin_o, phi_i);
          const Float4 forward = straight.eval(wo, wi) * Float4(std::fabs(wi.z));
          const Float4 backward = straight.eval(wi, wo) * Float4(std::fabs(wo.z));
          CAPTURE(sin_o);
          CAPTURE(phi_o);
          for (int k = 0; k < 4; ++k) CHECK(forward[k] == doctest::Approx(backward[k]).epsilon(2e-4));
        }
  }
  // Off the centreline the exit azimuths are offset by −2γo one way (R leaves at φ = −2γo, not +2γo): swapping
  // wo and wi moves wi from the R lobe's peak to the mirror side.
  const HairBsdf offset(along_x, 0.5f, Float4(0.0f), parameters(0.2f, 0.2f, 0.0f));
  const float peak = -2.0f * std::asin(0.5f);
  const Vec3 wo = fibre_direction(0.3f, 0.2f), wi = fibre_direction(-0.3f, 0.2f + peak);
  const float forward = offset.eval(wo, wi)[0] * std::fabs(wi.z), backward = offset.eval(wi, wo)[0] * std::fabs(wo.z);
  CHECK(forward > 2.0f * backward);
}

TEST_CASE("hair: grazing directions, the fibre's edges and extreme roughness give finite values") {
  std::mt19937 rng(11);
  const Vec3 wos[] = {{1.0f, 0.0f, 0.0f},  {-1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, fibre_direction(0.999999f, 0.3f),
                      fibre_direction(-0.9999f, -1.0f), {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, -1.0f}};
  for (const float beta_m : {0.001f, 0.01f, 1.0f})
    for (const float beta_n : {0.001f, 1.0f})
      for (const float h : {-1.0f, 1.0f, 0.0f})
        for (const float alpha : {0.0f, 2.0f, 45.0f}) {
          const HairBsdf bsdf({1.0f, 0.0f}, h, Float4(0.0f, 1.0f, 100.0f, 1e30f), parameters(beta_m, beta_n, alpha));
          for (const Vec3& wo : wos) {
            CAPTURE(beta_m);
            CAPTURE(beta_n);
            CAPTURE(h);
            CAPTURE(wo.x);
            CAPTURE(wo.z);
            for (int i = 0; i < 40; ++i) {
              const auto s = bsdf.sample(wo, test::uniform01(rng), {test::uniform01(rng), test::uniform01(rng)});
              if (!s) continue;  // allowed only for wi.z = 0 or a pdf that underflowed
              CHECK(std::isfinite(s->wi.x + s->wi.y + s->wi.z));
              CHECK(s->pdf[0] > 0.0f);
              CHECK(is_finite(s->f).all());
              CHECK(is_finite(s->pdf).all());
              CHECK(std::isfinite(s->hero_weight()[0]));
            }
            for (const Vec3& wi : wos) {
              CHECK(is_finite(bsdf.eval(wo, wi)).all());
              CHECK(is_finite(bsdf.pdf(wo, wi)).all());
              CHECK((bsdf.eval(wo, wi) >= Float4(0.0f)).all());
            }
            // The exact corners u = 0 and u → 1 of every uniform.
            for (const float u : {0.0f, 0.99999994f})
              if (const auto s = bsdf.sample(wo, u, {u, u})) CHECK(is_finite(s->f).all());
          }
        }
}

TEST_CASE("hair: sigma_a from a reflectance follows Chiang et al.'s Eq. 9") {
  // β_n = 0.3: the polynomial is 5.969 − 0.0645 + 0.2279 − 0.2897 + 0.0452 + 0.0006 = 5.8882, so c = 0.5 gives
  // (ln 0.5 / 5.8882)² = 0.013858; white needs none, darker needs more.
  const Float4 sigma_a = HairBsdf::sigma_a_from_reflectance(Float4(0.5f, 1.0f, 0.1f, 0.0f), 0.3f);
  CHECK(sigma_a[0] == doctest::Approx(0.013858).epsilon(1e-3));
  CHECK(sigma_a[1] == 0.0f);
  CHECK(sigma_a[2] > sigma_a[0]);
  CHECK(std::isfinite(sigma_a[3]));  // black is clamped to 1e-4
  CHECK(sigma_a[3] > sigma_a[2]);
}

TEST_CASE("hair material: the fibre's direction comes from dpdu and h from v, in the integrator's frame") {
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f / 470.0f));
  const Material hair = HairMaterial(std::make_shared<ConstantSpectrum>(0.4), parameters(0.25f, 0.35f));
  CHECK(hair.uses_tangents());
  const Vec3 n = normalize(Vec3{0.3f, -0.5f, 0.8f});
  const Vec3 along = normalize(cross(n, Vec3{1.0f, 0.0f, 0.0f}));  // a unit tangent
  MaterialContext context;
  context.shading_normal = context.geometric_normal = n;
  context.dpdu = along * 3.0f + n * 0.7f;  // scaled and leaning out of the tangent plane: projected away
  context.uv = {0.2f, 0.8f};               // h = 0.6
  const Bsdf bsdf = hair.bsdf(context, lambda);
  // The reference: the fibre frame built by hand, x = tangent, y = n × x, z = n, with the fibre along x.
  const HairBsdf reference({1.0f, 0.0f}, 0.6f, Float4(0.4f), parameters(0.25f, 0.35f));
  const Frame shading = Frame::from_normal(n);
  const Vec3 y = cross(n, along);
  const auto in_fibre = [&](Vec3 w) { return Vec3{dot(w, along), dot(w, y), dot(w, n)}; };
  std::mt19937 rng(5);
  for (int i = 0; i < 50; ++i) {
    const Vec3 wo = normalize(Vec3{test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f});
    const Vec3 wi = normalize(Vec3{test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f});
    const Float4 got = bsdf.eval(shading.to_local(wo), shading.to_local(wi));
    const Float4 want = reference.eval(in_fibre(wo), in_fibre(wi));
    for (int k = 0; k < 4; ++k) CHECK(got[k] == doctest::Approx(want[k]).epsilon(1e-3));
  }
  // No dpdu (hair on a mesh without tangents): the frame's first axis stands in; finite, not NaN.
  context.dpdu = {};
  CHECK(hair_fibre_direction(shading, context.dpdu).x == 1.0f);
  const Bsdf fallback = hair.bsdf(context, lambda);
  CHECK(is_finite(fallback.eval({0.0f, 0.6f, 0.8f}, {0.0f, -0.6f, 0.8f})).all());
}

TEST_CASE("hair material: at a curve hit the result does not depend on which way the normal faces about the fibre") {
  // A curve hit gives h relative to the ray (the offset along d × t, pbrt-v4's v) and a normal that faces the ray
  // (flat), points away from it (pbrt-v4's flat curves) or is the tube's (round). The model is symmetric about the
  // fibre and h is measured relative to wo, so all three must give the same f·|cos θi| (what the integrator uses):
  // were h read along a frame axis, the first two would mirror each other's highlights across the fibre (the
  // cuticle tilt and h ≠ 0 make f asymmetric).
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f / 470.0f));
  const Material hair = HairMaterial(std::make_shared<ConstantSpectrum>(0.3), parameters(0.2f, 0.3f, 3.0f));
  const Vec3 t = normalize(Vec3{0.2f, 1.0f, 0.1f});                       // the fibre
  const Vec3 d = normalize(Vec3{0.1f, -0.3f, 1.0f});                      // the camera ray
  const Vec3 b = normalize(d - t * dot(d, t));                            // d across the fibre
  const Vec3 a = cross(b, t);                                             // = normalize(d × t): the side h > 0
  const float h = 0.55f, s = std::sqrt(1.0f - h * h);
  const Vec3 normals[] = {-b, b, normalize(a * h - b * s)};               // facing, away, round tube
  MaterialContext context;
  context.dpdu = t * 2.0f;
  context.uv = {0.3f, 0.5f * (1.0f + h)};
  context.wo = -d;
  std::mt19937 rng(11);
  int asymmetric = 0;
  for (int i = 0; i < 40; ++i) {
    const Vec3 wi = normalize(Vec3{test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f, test::uniform01(rng) - 0.5f});
    Float4 first{};
    for (int k = 0; k < 3; ++k) {
      context.shading_normal = context.geometric_normal = normals[k];
      const Frame frame = Frame::from_normal(normals[k]);
      // f carries 1/|cos θi| about the shading normal, which the integrator's cosine cancels: compare f·|cos θi|.
      const Vec3 wi_local = frame.to_local(wi);
      const Float4 f = hair.bsdf(context, lambda).eval(frame.to_local(-d), wi_local) * Float4(std::fabs(wi_local.z));
      if (k == 0) first = f;
      for (int l = 0; l < 4; ++l) CHECK(f[l] == doctest::Approx(first[l]).epsilon(1e-3));
    }
    // The mirror image of wi across the plane of the fibre and the ray: not the same value (else the test could
    // not see a mirrored h).
    const Vec3 mirrored = wi - a * (2.0f * dot(wi, a));
    context.shading_normal = context.geometric_normal = normals[0];
    const Frame frame = Frame::from_normal(normals[0]);
    const Vec3 mirrored_local = frame.to_local(mirrored);
    const Float4 m = hair.bsdf(context, lambda).eval(frame.to_local(-d), mirrored_local) * Float4(std::fabs(mirrored_local.z));
    asymmetric += std::fabs(m[1] - first[1]) > 0.05f * std::fmax(m[1], first[1]);
  }
  CHECK(asymmetric > 10);
}

TEST_CASE("hair material: parameters out of range name what was expected") {
  const SpectrumPtr grey = std::make_shared<ConstantSpectrum>(0.4);
  HairParameters p;
  p.beta_m = 0.0f;
  CHECK_THROWS_WITH_AS(HairMaterial(grey, p), doctest::Contains("beta_m must lie in (0, 1]"), InputError);
  p = {};
  p.beta_n = 1.5f;
  CHECK_THROWS_WITH_AS(HairMaterial(grey, p), doctest::Contains("beta_n"), InputError);
  p = {};
  p.eta = 0.9f;
  CHECK_THROWS_WITH_AS(HairMaterial(grey, p), doctest::Contains("eta must be a finite number ≥ 1"), InputError);
  p = {};
  p.alpha_deg = 60.0f;
  CHECK_THROWS_WITH_AS(HairMaterial(grey, p), doctest::Contains("alpha"), InputError);
  CHECK_THROWS_AS(HairMaterial(nullptr, HairParameters{}), InputError);
}
