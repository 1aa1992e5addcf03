// The layered BSDF's deferred density (Bsdf::sample_deferring_density): the sample without its pdf() walk is the
// same direction with the same weight, and pdf(wo, wi) is exactly the density it left out; the volumetric path
// integrator, which evaluates that density only where a sampled direction reaches a light, keeps its MIS weights
// summing to one (its mean equals next-event estimation alone on a rough-coated plane under a uniform sky).
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "media_test_scene.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/bsdfs/material.h"
#include "transport/sampling/sampler.h"
#include "transport/textures/spectral_texture.h"

using namespace rimu;

namespace {

LayeredBsdf layered(float roughness, LayerBase base, LayerMedium medium) {
  const float alpha = TrowbridgeReitz::roughness_to_alpha(roughness);
  return LayeredBsdf(1.5f, TrowbridgeReitz(alpha, alpha), base, medium, LayerWalk{});
}

/// The plane z = 0 (normal +z) of material 0, infinite.
class PlaneGeometry final : public RayQueries {
 public:
  std::optional<SurfaceHit> intersect(const Ray& ray) const override {
    if (ray.direction.z == 0.0f) return std::nullopt;
    const float t = -ray.origin.z / ray.direction.z;
    if (!(t > ray.t_min) || !(t < ray.t_max)) return std::nullopt;
    SurfaceHit hit;
    hit.t = t;
    hit.position = ray.origin + ray.direction * t;
    hit.position.z = 0.0f;
    hit.geometric_normal = hit.shading_normal = Vec3{0.0f, 0.0f, 1.0f};
    hit.dpdu = {1.0f, 0.0f, 0.0f};
    hit.dpdv = {0.0f, 1.0f, 0.0f};
    hit.material = 0;
    return hit;
  }
  bool occluded(const Ray& ray) const override { return intersect(ray).has_value(); }
};

}  // namespace

TEST_CASE("layered: sample() without its density draws the same direction and weight, pdf(wo, wi) is that density") {
  const LayerMedium slab{0.2f, Float4(0.5f), 0.3f};
  const ConductorBsdf smooth_gold(Float4(0.2f, 0.4f, 0.6f, 0.8f), Float4(3.0f), TrowbridgeReitz(0.0f, 0.0f));
  struct Case {
    const char* name;
    LayeredBsdf bsdf;
  };
  const Case cases[] = {
      {"rough coat over a Lambertian, scattering slab", layered(0.3f, DiffuseBsdf(Float4(0.8f, 0.6f, 0.4f, 0.2f)), slab)},
      {"smooth coat over a Lambertian (delta reflections and walks)", layered(0.0f, DiffuseBsdf(Float4(0.7f)), slab)},
      {"smooth coat over a smooth metal, clear (delta only)", layered(0.0f, smooth_gold, LayerMedium{0.0f, Float4(0.0f), 0.0f})},
  };
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const Bsdf bsdf(c.bsdf);
    int deferred = 0, compared = 0;
    for (int i = 0; i < 4000; ++i) {
      // wo on either side (the BSDF is two-sided: the lower side is mirrored inside).
      const float cos_o = (i % 2 ? -1.0f : 1.0f) * (0.02f + 0.98f * uniform(rng));
      const float phi = 6.2831853f * uniform(rng), s = std::sqrt(1.0f - cos_o * cos_o);
      const Vec3 wo{s * std::cos(phi), s * std::sin(phi), cos_o};
      const float u_lobe = uniform(rng);
      const Vec2 u{uniform(rng), uniform(rng)};
      const auto full = bsdf.sample(wo, u_lobe, u);
      const auto lazy = bsdf.sample_deferring_density(wo, u_lobe, u);
      REQUIRE(full.has_value() == lazy.has_value());
      if (!full) continue;
      ++compared;
      CHECK(!full->density_deferred);
      CHECK(lazy->is_delta == full->is_delta);
      // The same walk: the direction to the bit.
      CHECK(lazy->wi.x == full->wi.x);
      CHECK(lazy->wi.y == full->wi.y);
      CHECK(lazy->wi.z == full->wi.z);
      // Deferred exactly where the density would have come from pdf(): every non-delta sample.
      CHECK(lazy->density_deferred == !full->is_delta);
      if (!lazy->density_deferred) continue;
      ++deferred;
      CHECK((lazy->pdf == Float4(1.0f)).all());
      // pdf() is a deterministic function of (wo, wi), so the density evaluated later is the one sample() returned.
      CHECK(bsdf.pdf(wo, lazy->wi)[0] == full->pdf[0]);
      // The weight f·|cos θi|/pdf: full's is weight·pdf/|cos|·|cos|/pdf, four float roundings (≤ 2.4e-7 relative).
      const float cos_i = std::fabs(lazy->wi.z);
      const Float4 w_full = full->f * Float4(cos_i / full->pdf[0]);
      const Float4 w_lazy = lazy->f * Float4(cos_i);
      for (int k = 0; k < 4; ++k) {
        CAPTURE(k);
        CHECK(std::fabs(w_lazy[k] - w_full[k]) <= 1e-6f * std::fabs(w_full[k]) + 1e-30f);
      }
    }
    CHECK(compared > 1000);  // most walks leave through the coat
    if (std::string(c.name).find("delta only") != std::string::npos) CHECK(deferred == 0);
    else CHECK(deferred > 100);
  }
}

TEST_CASE("Bsdf::sample_deferring_density: other BSDFs sample with their density as before") {
  const Bsdf diffuse(DiffuseBsdf(Float4(0.5f)));
  const Bsdf glass(DielectricBsdf(Float4(1.5f), TrowbridgeReitz(0.1f, 0.1f)));
  CHECK(!diffuse.evaluation_is_costly());
  CHECK(!glass.evaluation_is_costly());
  CHECK(Bsdf(layered(0.3f, DiffuseBsdf(Float4(0.5f)), LayerMedium{})).evaluation_is_costly());
  for (const Bsdf* b : {&diffuse, &glass}) {
    const Vec3 wo = normalize(Vec3{0.3f, -0.2f, 0.9f});
    const auto full = b->sample(wo, 0.7f, {0.25f, 0.6f});
    const auto lazy = b->sample_deferring_density(wo, 0.7f, {0.25f, 0.6f});
    REQUIRE(full);
    REQUIRE(lazy);
    CHECK(!lazy->density_deferred);
    CHECK((lazy->pdf == full->pdf).all());
    CHECK((lazy->f == full->f).all());
  }
}

TEST_CASE("volumetric integrator: MIS with deferred layered densities has the mean of next-event estimation alone") {
  // One bounce off a rough-coated plane under a uniform sky of radiance 1: the radiance is the coat's directional
  // albedo. With MIS, a sampled direction that escapes to the sky takes the weight of the density deferred at the
  // plane; next-event estimation alone (every sampled direction's light dropped) needs no density. Both are
  // unbiased, so their means agree within their standard errors only if the deferred density is the one MIS uses
  // for the light technique too (a weight built from any other density would not sum to one with it).
  PlaneGeometry geometry;
  const auto albedo = std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(0.8));
  CoatLayer layer;
  layer.roughness = 0.3f;
  layer.thickness = 0.1f;
  std::vector<Material> materials{CoatedDiffuseMaterial(albedo, std::make_shared<ConstantSpectrum>(1.5), layer)};
  std::vector<std::unique_ptr<Light>> lights;
  lights.push_back(std::make_unique<test::UniformSky>(1.0f));
  const double power[] = {1.0};
  const PowerLightSampler light_sampler(power);
  TransportScene surfaces;
  surfaces.geometry = &geometry;
  surfaces.materials = &materials;
  surfaces.lights = &lights;
  surfaces.light_sampler = &light_sampler;
  surfaces.infinite_lights = {0};
  const std::vector<Medium> media;
  const std::vector<MediumBoundary> boundaries;
  const VolumetricScene scene{surfaces, &media, &boundaries};

  auto render = [&](DirectLighting strategy, uint64_t seed) {
    VolumetricIntegratorSettings settings;
    settings.path.max_depth = 1;
    settings.path.direct_lighting = strategy;
    const VolumetricPathIntegrator integrator(scene, settings);
    IndependentSampler sampler(seed);
    const Ray ray{{0.0f, 0.0f, 1.0f}, normalize(Vec3{0.6f, 0.0f, -0.8f})};
    return test::lane_statistics(40000, [&](int i) {
      sampler.start_pixel_sample(i, 0, 0);
      return test::rotated_radiance(integrator, ray, sampler, i);
    });
  };
  const test::LaneStatistics mis = render(DirectLighting::mis, 1);
  const test::LaneStatistics nee = render(DirectLighting::nee_only, 2);
  CHECK(mis.non_finite == 0);
  CHECK(nee.non_finite == 0);
  for (int k = 0; k < 4; ++k) {
    CAPTURE(k);
    CAPTURE(mis.mean[k]);
    CAPTURE(nee.mean[k]);
    CAPTURE(mis.standard_error[k]);
    CAPTURE(nee.standard_error[k]);
    // A coat over a white-ish base reflects a good part of the sky, and less than all of it.
    CHECK(mis.mean[k] > 0.3);
    CHECK(mis.mean[k] < 1.0);
    // 5 combined standard errors: a normal deviation that large has probability 6e-7.
    const double sigma = std::hypot(mis.standard_error[k], nee.standard_error[k]);
    CHECK(std::fabs(mis.mean[k] - nee.mean[k]) <= 5.0 * sigma);
  }
}
