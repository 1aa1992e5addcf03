// The hero-wavelength unidirectional path tracer: spectral MIS over four lanes, NEE + BSDF sampling with MIS.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "spectral/wavelengths/wavelength_density.h"
#include "transport/lights/light.h"
#include "transport/lights/light_sample.h"
#include "transport/lights/light_sampler.h"
#include "transport/bsdfs/material.h"
#include "transport/geometry/ray.h"
#include "transport/geometry/ray_differentials.h"
#include "transport/integrators/light_group_radiance.h"
#include "transport/integrators/metropolis_settings.h"
#include "transport/integrators/ray_queries.h"
#include "transport/integrators/vertex_merging.h"
#include "transport/sampling/sampler.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

class GuidingField;    // transport/guiding/guiding_field.h
struct GuidingSample;
class DaylightRaySampler;   // transport/lights/daylight_ray_sampler.h

/// What the integrator needs of a scene: geometry queries, materials by index, lights by index, and how lights
/// are picked. Non-owning; the render side owns everything and keeps it alive while rendering.
struct TransportScene {
  const RayQueries* geometry = nullptr;
  const std::vector<Material>* materials = nullptr;
  const std::vector<std::unique_ptr<Light>>* lights = nullptr;
  const LightSampler* light_sampler = nullptr;
  std::vector<int> infinite_lights;  ///< indices of lights with is_infinite(): seen by escaping rays
  float scene_scale = 1.0f;          ///< bounding-box diagonal, for scale-aware ray offsets
  /// Some material lets shadow rays through (Material::passes_shadow_rays: a pane): shadow rays then trace closest
  /// hits through them (transport/integrators/shadow_passage.h); false keeps the single occlusion query.
  bool passable_surfaces = false;
  /// Some material reads an image texture or a bump map: the integrator then computes each hit's footprint
  /// (MaterialContext::dpdx … duvdy) from the camera ray's differentials, following them through specular bounces.
  /// False (the default) skips that work and leaves the footprint zero.
  bool texture_footprints = false;
  /// Something moves while the shutter is open (EmbreeScene::has_motion): each camera sample then draws a time in
  /// [0, 1] that its rays carry (Ray::time). False keeps every ray at time 0 and the sampler's dimensions as they were.
  bool has_motion = false;
  /// Rays of the scene's distant lights and portal skies through its apertures, for the daylit-point technique
  /// (transport/integrators/daylit_connection.h); nullptr where the scene has neither or the technique is off.
  const DaylightRaySampler* daylight_rays = nullptr;
  /// The density camera paths draw wavelengths from (spectral/wavelengths/wavelength_density.h); nullptr: the visible density.
  const TabulatedWavelengthDensity* wavelength_density = nullptr;
};

/// How light sources are found (the default combines both; the others exist to check the combination).
enum class DirectLighting {
  mis,        ///< next-event estimation and BSDF sampling, power heuristic
  nee_only,   ///< only next-event estimation sees non-delta emitters (BSDF-sampled hits on lights add nothing)
  bsdf_only,  ///< no next-event estimation: lights are found only by BSDF sampling (delta lights are then invisible)
};

struct PathIntegratorSettings {
  int max_depth = 16;         ///< the number of surface interactions after which a path ends
  int russian_roulette_depth = 3;  ///< from this depth on, paths are terminated with probability 1 − q
  WavelengthMode wavelengths = WavelengthMode::hero;
  DirectLighting direct_lighting = DirectLighting::mis;
  /// Path guiding (transport/guiding/, docs/transport.md "Path guiding"): the render loop learns the incident light
  /// pass by pass and the integrator samples from it at non-delta vertices. Off by default.
  bool guiding = false;
  /// What the field's leaves learn: a directional quadtree (Müller et al. 2017) or a parallax-aware vMF mixture
  /// (Ruppert et al. 2020; transport/guiding/vmf_mixture.h). `"guiding": "mixture"` in a scene.
  bool guiding_mixture = false;
  /// α: the probability of drawing a guided vertex's direction from the learned field (else from the BSDF).
  float guiding_probability = 0.5f;
  /// Daylit points (transport/integrators/daylit_connection.h, docs/transport.md "Daylit points"): each path traces
  /// one ray of daylight (a sun, a sky with portals) into the scene and connects its diffuse and glossy vertices to
  /// the point it lights, with MIS against next-event estimation and BSDF sampling there. Only with
  /// `direct_lighting` mis and where the scene has TransportScene::daylight_rays (the loader sets both).
  bool daylit_points = false;
  /// At vertices with a glossy lobe (BsdfFlags::has_glossy), next-event estimation draws this many candidate lights
  /// and keeps one by what the BSDF passes from it (transport/integrators/light_resampling.h); 1 turns it off.
  /// 0 (the default): kManyLightsCandidates in scenes with at least kManyLights lights, else 1 (what it gains grows
  /// with the lights competing for a lobe, its cost does not: docs/benchmarks.md, "Glossy vertices").
  int glossy_light_candidates = 0;
  /// Caustics of the lights that sample emission (Light::samples_emission) by light tracing
  /// (transport/integrators/caustic_light_tracer.h): the path tracer leaves out their paths E D S⁺ L (a camera ray's
  /// first vertex sampled by a non-delta lobe, every later one by a delta lobe, then such a light), which the render
  /// loop's light tracer adds. Off by default; the render loop turns it on only where it also traces them.
  bool caustic_light_tracing = false;
  /// Bidirectional path tracing (transport/integrators/bidirectional_path_integrator.h) instead of the path tracer:
  /// `"integrator": {"method": "bidirectional"}`. The render loop uses it only where it can (a camera light paths
  /// connect to, no media, no adaptive sampling) and falls back to the path tracer elsewhere.
  bool bidirectional = false;
  /// Vertex merging on top of it (transport/integrators/vertex_merging.h): `"method": "vcm"`. Only with
  /// `bidirectional`.
  bool vertex_merging = false;
  VertexMergingSettings merging;
  /// Metropolis light transport over this path tracer (render/metropolis_renderer.h): `"method": "metropolis"`. The
  /// render loop uses it where it can (no adaptive sampling, feature buffers, light groups, spectral bins or sample
  /// clamp) and falls back to the path tracer elsewhere.
  bool metropolis = false;
  MetropolisSettings metropolis_settings;
  static constexpr int kManyLights = 8;
  static constexpr int kManyLightsCandidates = 8;
  /// The candidates per glossy vertex in a scene of `light_count` lights.
  int glossy_candidates_for(size_t light_count) const {
    if (glossy_light_candidates > 0) return glossy_light_candidates;
    return light_count >= size_t(kManyLights) ? kManyLightsCandidates : 1;
  }
};

/// What a path does for guiding: sample from `field` (nullptr: not yet learned) and append what it learned to
/// `record` (nullptr: nothing is recorded), at most until `record` holds `record_limit` samples.
struct PathGuidingContext {
  const GuidingField* field = nullptr;
  std::vector<GuidingSample>* record = nullptr;
  size_t record_limit = 0;
};

/// Estimates the radiance arriving along camera rays, per lane (see docs/transport.md for the estimator).
///
/// Dimension order per camera sample (every estimator draws the same dimension for the same decision):
/// the render loop draws 0-1 film position, 2-3 lens, 4 wavelength; then per bounce, in this order:
/// light choice (1), light position (2), BSDF lobe (1), BSDF direction (2), Russian roulette (1). With daylit
/// points, the first vertex draws the daylight ray first: its light (1), direction (2) and aperture point (2).
class PathIntegrator {
 public:
  PathIntegrator(const TransportScene& scene, PathIntegratorSettings settings) : scene_(scene), settings_(settings) {}

  /// Radiance along `ray` at the four wavelengths, in W/(m²·sr·nm): lane j is this path's estimate for λⱼ,
  /// already weighted by spectral MIS, so the film's mean over lanes of Lⱼ c(λⱼ)/p(λⱼ) is unbiased.
  SampledSpectrum radiance(const Ray& ray, const SampledWavelengths& lambda, Sampler& sampler) const {
    return radiance(ray, lambda, sampler, PathGuidingContext{});
  }
  /// The same, guided by (and teaching) the field in `guiding` when settings.guiding is on, and with each light
  /// group's share of the result added to `groups` (light_group_radiance.h; nothing when groups.groups is null).
  SampledSpectrum radiance(const Ray& ray, const SampledWavelengths& lambda, Sampler& sampler,
                           const PathGuidingContext& guiding, const LightGroupRadiance& groups = {}) const {
    return radiance(ray, nullptr, lambda, sampler, guiding, groups);
  }
  /// The same with the camera ray's differentials (nullptr: none), which give textured hits their footprint when
  /// the scene has texture_footprints.
  SampledSpectrum radiance(const Ray& ray, const RayDifferentials* differentials, const SampledWavelengths& lambda,
                           Sampler& sampler, const PathGuidingContext& guiding,
                           const LightGroupRadiance& groups = {}) const;
  const TransportScene& scene() const { return scene_; }

 private:
  const TransportScene& scene_;
  PathIntegratorSettings settings_;
};

/// The origin of a ray leaving `position` on the side `normal`·`direction` > 0, offset against self-intersection
/// by a distance that scales with the magnitude of the coordinates (float spacing) and the scene's size.
Vec3 offset_ray_origin(Vec3 position, Vec3 geometric_normal, Vec3 direction, float scene_scale);
/// The same for a ray leaving a surface hit: the offset also covers the rounding of the coordinates the hit point
/// was computed from (SurfaceHit::position_scale), which near the world origin exceeds |p|'s.
Vec3 offset_ray_origin(const SurfaceHit& hit, Vec3 direction, float scene_scale);

/// What a shadow ray for the light sample `ls`, drawn at `reference`, tests: the direction and length from `origin`
/// (reference lifted off its surface by offset_ray_origin, or reference itself in a medium) to the sampled point,
/// itself lifted off the light's surface (ls.normal) towards the reference by the same rule. Aiming from the lifted
/// origin matters near an emitter: a ray along ls.wi from the lifted origin meets a plane the sample lies on earlier
/// by offset/cos, and for a receiver within a few cm of the light at grazing angles that is more than any relative
/// margin on the length, so the light's own surface would shadow the sample (docs/transport.md, "Shadow rays near
/// emitters"). Lights at infinity: ls.wi and an infinite length. Callers shorten the length by 2⁻¹² for rounding.
struct ShadowSegment {
  Vec3 direction;
  float length = 0.0f;
};
ShadowSegment shadow_segment(Vec3 origin, Vec3 reference, const LightSample& ls, float scene_scale);
/// The segment from `origin` to `target`, both already lifted off their surfaces; length 0 (and
/// `fallback_direction`) when they coincide or the distance is not finite.
ShadowSegment shadow_segment(Vec3 origin, Vec3 target, Vec3 fallback_direction);

}  // namespace rimu
