// VolumetricIntegratorSettings::max_depth_includes_media (pbrt-v4 volpath's depth rule): scattering events in media
// count towards max_depth. A furnace slab (uniform sky of radiance 1, albedo 1, index-matched boundaries, so no
// surface interaction counts) has closed forms per scattering order: the unscattered part exp(−τ) and single
// scattering, which max_depth 0 and 1 must give exactly; without the rule every max_depth gives the furnace's 1.
#include <doctest/doctest.h>

#include <cmath>

#include "media_test_scene.h"
#include "transport/sampling/sampler.h"

namespace rimu {
namespace {

// Optical thicknesses of the 1 m slab per lane (σ_s in 1/m, σ_a = 0).
const Float4 kTau(0.25f, 0.5f, 1.0f, 2.0f);

test::LaneStatistics render_slab(int max_depth, bool includes_media, int count, uint64_t seed,
                                 bool medium_counts_towards_max_depth = true, float boundary_ior = 0.0f) {
  const test::SlabScene slab(1.0f,
                             Medium(HomogeneousMedium(test::bands(Float4(0.0f)), test::bands(kTau), 0.0f), 0,
                                    medium_counts_towards_max_depth),
                             std::make_unique<test::UniformSky>(1.0f), boundary_ior);
  VolumetricIntegratorSettings s;
  s.path.max_depth = max_depth;
  s.max_depth_includes_media = includes_media;
  const VolumetricPathIntegrator integrator(slab.scene, s);
  IndependentSampler sampler(seed);
  const Ray ray{{0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}};  // normal incidence through z = 0 .. 1
  return test::lane_statistics(count, [&](int i) {
    sampler.start_pixel_sample(i, 0, 0);
    return test::rotated_radiance(integrator, ray, sampler, i);
  });
}

// E₂(x) = ∫₀¹ exp(−x/μ) dμ: the share of an isotropic point's radiance from a uniform sky that crosses a slab
// distance x (along the normal) unscattered, over one hemisphere, is ½E₂(x). Midpoint rule, error ~1e-7.
double e2(double x) {
  constexpr int n = 4000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += std::exp(-x / ((i + 0.5) / n));
  return sum / n;
}

// Once-scattered radiance along the normal through a non-absorbing slab of optical thickness τ under a uniform sky
// of radiance 1, isotropic phase: ∫₀¹ τ e^{−τz} · ½[E₂(τ(1−z)) + E₂(τz)] dz (scatter at depth z, then the sky seen
// unscattered towards either face).
double single_scattering(double tau) {
  constexpr int n = 800;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = (i + 0.5) / n;
    sum += tau * std::exp(-tau * z) * 0.5 * (e2(tau * (1.0 - z)) + e2(tau * z));
  }
  return sum / n;
}

void check_lanes(const test::LaneStatistics& s, const double expected[4]) {
  CHECK(s.non_finite == 0);
  for (int k = 0; k < 4; ++k) {
    CAPTURE(k);
    CAPTURE(s.mean[k]);
    CAPTURE(expected[k]);
    CAPTURE(s.standard_error[k]);
    // 5 standard errors (a normal deviation that large: probability 6e-7), 1e-5 for lanes estimated exactly.
    CHECK(std::fabs(s.mean[k] - expected[k]) <= 5.0 * s.standard_error[k] + 1e-5);
  }
}

}  // namespace

TEST_CASE("max_depth_includes_media: max_depth 0 keeps no light scattered in the medium, 1 single scattering") {
  double unscattered[4], once[4];
  for (int k = 0; k < 4; ++k) {
    unscattered[k] = std::exp(-double(kTau[k]));
    once[k] = unscattered[k] + single_scattering(kTau[k]);
  }
  // The closed form's own check: single scattering lies between nothing and everything the furnace has left.
  for (int k = 0; k < 4; ++k) CHECK((once[k] > unscattered[k] && once[k] < 1.0));
  check_lanes(render_slab(0, true, 20000, 3), unscattered);
  check_lanes(render_slab(1, true, 40000, 5), once);
  // Single scattering is what separates them: at τ = 2, 0.135 against about 0.5 (far beyond 5σ).
  CHECK(once[3] - unscattered[3] > 0.2);
}

TEST_CASE("max_depth_includes_media: the mean rises with max_depth towards the furnace's 1, without it, 1 at any depth") {
  const double furnace[4] = {1.0, 1.0, 1.0, 1.0};
  // Without the rule the index-matched slab has no surface interaction to count: every depth is the full furnace.
  check_lanes(render_slab(0, false, 20000, 7), furnace);
  check_lanes(render_slab(2, false, 20000, 7), furnace);
  // With it: the same seeds give each path the same random numbers up to where the smaller depth ends it, so each
  // estimate can only gain light with depth (sky seen after one more scattering), never lose any.
  double previous[4] = {0.0, 0.0, 0.0, 0.0};
  for (int depth = 0; depth <= 6; ++depth) {
    const test::LaneStatistics s = render_slab(depth, true, 20000, 11);
    CAPTURE(depth);
    for (int k = 0; k < 4; ++k) {
      CAPTURE(k);
      CHECK(s.mean[k] >= previous[k]);
      CHECK(s.mean[k] <= 1.0 + 5.0 * s.standard_error[k]);
      previous[k] = s.mean[k];
    }
  }
  // τ = 0.25 scatters rarely: by depth 6 all but a negligible share of the furnace is kept; τ = 2 still misses the
  // higher orders (a multiple of its standard error below 1).
  const test::LaneStatistics deep = render_slab(6, true, 20000, 11);
  CHECK(deep.mean[0] == doctest::Approx(1.0).epsilon(0.01));
  CHECK(deep.mean[3] < 1.0 - 5.0 * deep.standard_error[3]);
}

TEST_CASE("max_depth_includes_media: a medium whose vertices do not count (a subsurface walk) keeps every order") {
  // The walk has no depth of its own: in the index-matched slab (no entry vertex at all) max_depth 0 and 1 keep
  // the furnace's 1, where the counted medium keeps the unscattered light and single scattering (the first case).
  const double furnace[4] = {1.0, 1.0, 1.0, 1.0};
  check_lanes(render_slab(0, true, 20000, 13, false), furnace);
  check_lanes(render_slab(1, true, 20000, 13, false), furnace);
  const test::LaneStatistics counted = render_slab(1, true, 20000, 13, true);
  CHECK(counted.mean[3] < 1.0 - 5.0 * counted.standard_error[3]);
  // Behind glass faces (η 1.5: light reflects inside them, totally beyond 41.8°) the entry is a surface vertex of
  // depth 1; the walk's scattering and its internal reflections add none, so max_depth 1 still keeps all of the
  // lossless furnace. Counted, the same seeds lose the higher orders and the reflected light.
  check_lanes(render_slab(1, true, 20000, 17, false, 1.5f), furnace);
  const test::LaneStatistics counted_glass = render_slab(1, true, 20000, 17, true, 1.5f);
  for (int k = 0; k < 4; ++k) CHECK(counted_glass.mean[k] < 1.0 - 5.0 * counted_glass.standard_error[k]);
}

}  // namespace rimu
