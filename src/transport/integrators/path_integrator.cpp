#include "transport/integrators/path_integrator.h"
#include "transport/integrators/path_start_vertex.h"

#include <cmath>
#include <optional>

#include "transport/geometry/frame.h"
#include "transport/guiding/guided_bsdf.h"
#include "transport/guiding/path_guiding_record.h"
#include "transport/integrators/light_resampling.h"
#include "transport/integrators/path_footprint.h"
#include "transport/integrators/shadow_passage.h"
#include "transport/integrators/daylit_connection.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {
namespace {


// The shading frame at a hit, flipped for opaque (two-sided) materials so that wo is on the +z side.
struct ShadingContext {
  Frame frame;
  Vec3 geometric_normal;  // on the same side as the shading normal
};

// Inlined: trace_path has two instantiations (with and without light groups), and GCC then stops inlining this
// small function on its own, which costs the ungrouped path ~2 % of trace_path's instructions.
[[gnu::always_inline]] inline ShadingContext shading_context(const MaterialContext& hit, bool two_sided) {
  Vec3 ns = hit.shading_normal, ng = hit.geometric_normal;
  if (two_sided && dot(hit.wo, ng) < 0.0f) {
    ns = -ns;
    ng = -ng;
  }
  return {Frame::from_normal(ns), ng};
}

}  // namespace

Vec3 offset_ray_origin(Vec3 position, Vec3 geometric_normal, Vec3 direction, float scene_scale) {
  // Float coordinates near |p| carry a rounding error of ~|p|·2⁻²⁴ per operation; Embree's hit point adds a few.
  // 2⁻¹⁸·|p| is a safe margin; the scene-scale term covers points near the origin of a large scene.
  const float magnitude = std::fmax(max_component(abs(position)), 1e-4f * scene_scale);
  const float offset = magnitude * 0x1p-18f;
  return position + face_forward(geometric_normal, direction) * offset;
}

Vec3 offset_ray_origin(const SurfaceHit& hit, Vec3 direction, float scene_scale) {
  const float magnitude =
      std::fmax(std::fmax(max_component(abs(hit.position)), hit.position_scale), 1e-4f * scene_scale);
  return hit.position + face_forward(hit.geometric_normal, direction) * (magnitude * 0x1p-18f);
}

ShadowSegment shadow_segment(Vec3 origin, Vec3 target, Vec3 fallback_direction) {
  const Vec3 to_target = target - origin;
  const float distance = length(to_target);
  if (!(distance > 0.0f) || !std::isfinite(distance)) return {fallback_direction, 0.0f};
  return {to_target / distance, distance};
}

ShadowSegment shadow_segment(Vec3 origin, Vec3 reference, const LightSample& ls, float scene_scale) {
  if (!std::isfinite(ls.distance)) return {ls.wi, ls.distance};
  Vec3 target = reference + ls.wi * ls.distance;
  if (!(ls.normal == Vec3{})) target = offset_ray_origin(target, ls.normal, -ls.wi, scene_scale);
  return shadow_segment(origin, target, ls.wi);
}

namespace {

// PathIntegrator::radiance, and radiance_from_vertex (path_start_vertex.h) when `start` is given. The scene and
// settings keep the members' names, so the body reads as the member function it was. kGrouped: the film has light
// groups and `groups` receives each contribution's share; without, the per-group code is compiled out, so a scene
// without groups runs the same instructions as before groups existed.
template <bool kGrouped>
SampledSpectrum trace_path(const TransportScene& scene_, const PathIntegratorSettings& settings_, const Ray& camera_ray,
                           const RayDifferentials* camera_differentials, const SampledWavelengths& lambda,
                           Sampler& sampler, const PathGuidingContext& guiding, const PathStartVertex* start,
                           const LightGroupRadiance& groups) {
  const auto& lights = *scene_.lights;
  const LightSampler& light_sampler = *scene_.light_sampler;

  SampledSpectrum radiance(0.0f);
  // R_k = p(x̄ | λ_k) / p(x̄ | hero). Single-wavelength mode makes the partners' techniques absent (R_k = 0), so
  // the hero's estimate is 4·β·L (the film averages four lanes) and the partners' outputs are masked to zero.
  // Independent and rgb modes keep R_k = 1 (every lane weighted by the hero's density; transport/sampling/wavelength_modes.h).
  const LaneTechniques lanes{settings_.wavelengths};
  const bool single = settings_.wavelengths == WavelengthMode::single;
  SampledSpectrum pdf_ratio = lanes.initial_ratios();
  SampledSpectrum beta = pdf_ratio;  // f / p(x̄ | hero), per lane
  // Π η'² over the refractions so far: beta × eta_scale is the throughput without radiance scaling (BsdfSample::eta).
  float eta_scale = 1.0f;
  Ray ray = camera_ray;
  // The footprint of the current segment: the camera's, kept through specular bounces and panes, dropped after a
  // diffuse or glossy one (its spread is then the BSDF's, far wider than a pixel's: textures are point-sampled, and
  // the Monte Carlo average over many paths filters them).
  std::optional<RayDifferentials> differentials;
  if (scene_.texture_footprints && camera_differentials) differentials = *camera_differentials;

  // Path guiding: what this path teaches the field (if it records), and whether it may sample from one.
  const bool guiding_on = settings_.guiding;
  const bool recording = guiding_on && guiding.record && guiding.record->size() < guiding.record_limit;
  std::optional<PathGuidingRecord> record;
  if (recording) record.emplace(guiding_lane_weights(lambda, settings_.wavelengths == WavelengthMode::rgb));
  // Every emitted contribution, credited to its light's group as well (light_group_radiance.h).
  // What the field learns at a vertex is the light next-event estimation does not already sample well: an
  // emitter that the vertex's own sampled ray hit, weighted by MIS against NEE (`direct_by_mis`), is left out of
  // that vertex's record (it is indirect light for the vertices before it, and kept there). Learning it sent half
  // of the guided rays of a wall towards the window, whose sky NEE samples through its portal anyway
  // (docs/benchmarks.md, "Path guiding"). previous_recorded: the last bounce's vertex is the record's last one.
  bool previous_recorded = false;
  auto contribute = [&](const SampledSpectrum& contribution, const Light& light, bool direct_by_mis = false) {
    radiance += contribution;
    if constexpr (kGrouped) groups.add(light.light_group(), contribution);
    if (record) record->add_radiance(contribution, direct_by_mis && previous_recorded);
  };

  // What the previous bounce left for MIS when this segment hits a light.
  bool previous_specular = true;     // the camera "bounce" cannot be matched by light sampling
  float previous_hero_pdf = 1.0f;    // q_{0,bsdf}
  float previous_sum_ratio = sum(pdf_ratio);  // Σ_k R_k before the bounce
  float previous_bsdf_sum = sum(pdf_ratio);   // S_bsdf = Σ_k R_k q_{k,bsdf} (in units of the prefix's hero density)
  LightReference previous_reference{};
  LightSamplingPoint previous_sampling_point{};  // where the light sampler chose for the previous vertex
  // How many times its light sampler's density the previous vertex's MIS weights count: its candidates where it
  // chose its light among several (light_resampling.h), 1 elsewhere (see the next-event estimation below).
  float previous_light_boost = 1.0f;
  if (start) {  // a vertex the caller sampled with a wavelength-independent density: S_bsdf = q Σ_k R_k
    previous_specular = false;
    previous_hero_pdf = start->direction_pdf;
    previous_bsdf_sum = start->direction_pdf * previous_sum_ratio;
    previous_reference = start->reference;
    previous_sampling_point = start->sampling_point;
  }

  // Adds an emitter seen along the sampled direction: spectral MIS, and power-heuristic MIS against light sampling.
  const DirectLighting strategy = settings_.direct_lighting;
  // choice_probability: the light sampler's probability of this light (and part) at the previous vertex; where it is
  // 1 that vertex had a single light to give and did not resample, so its weights count the density once.
  // s_daylit: the daylit-point technique's density of this path (0 for every other light).
  auto add_emission = [&](const SampledSpectrum& emitted, float light_pdf_solid_angle, float choice_probability,
                          const Light& light, float s_daylit = 0.0f) {
    // NEE-only: a non-delta bounce leaves emitters to next-event estimation (which then takes full weight).
    if (strategy == DirectLighting::nee_only && !previous_specular) return;
    if (strategy == DirectLighting::bsdf_only) light_pdf_solid_angle = 0.0f;
    // Full weight where no other technique makes this path (a daylit point can where light sampling cannot).
    if (previous_specular || (light_pdf_solid_angle <= 0.0f && !(s_daylit > 0.0f))) {
      contribute(beta * emitted * Float4(kLanes / sum(pdf_ratio)), light);
      return;
    }
    const float boost = choice_probability < 1.0f ? previous_light_boost : 1.0f;
    const float s_light = boost * light_pdf_solid_angle * previous_sum_ratio;
    const float s_bsdf = previous_bsdf_sum;
    const float weight = previous_hero_pdf * s_bsdf / (s_light * s_light + s_bsdf * s_bsdf + s_daylit * s_daylit);
    contribute(beta * emitted * Float4(kLanes * weight), light, true);
  };

  const int glossy_candidates = settings_.glossy_candidates_for(lights.size());

  // Daylit points (daylit_connection.h): one daylight ray per path, traced when a first vertex connects to it.
  const DaylightRaySampler* daylight_rays = settings_.daylit_points && strategy == DirectLighting::mis &&
                                                    scene_.daylight_rays && !scene_.daylight_rays->empty()
                                                ? scene_.daylight_rays
                                                : nullptr;
  std::optional<DaylightRaySampler::DaylightRay> daylight_ray;
  std::optional<DaylitPoint> daylit;
  bool daylit_traced = false;
  // The previous vertex connected to the daylight ray's point (the technique exists for the path through it), and
  // what that makes of its density at this vertex and the one before: B's density relative to the prefix is
  // daylit_factor · p(y, ω) (daylit_connection.h), 0 where B cannot make the path.
  bool previous_connects = false;
  float previous_daylit_factor = 0.0f;
  Vec3 previous_position{}, previous_geometric_normal{};
  float segment_length = 0.0f;  // from the last scattering vertex along the current line (panes do not break it)

  // Panes passed straight through (docs/transport.md, "Glazing"): since the last scattering vertex (at most
  // kMaxShadowPassages, as for shadow rays), and in all (they do not count towards max_depth).
  int passages_since_vertex = 0, passages = 0;
  // Caustic light tracing (caustic_light_tracer.h): 1 after a camera ray's first vertex sampled a non-delta lobe
  // (E D), 2 once delta lobes followed (E D S⁺), 0 otherwise. An emitter it traces, hit in state 2, is left to it.
  int caustic_state = 0;
  for (int depth = 0;; ++depth) {
    const std::optional<SurfaceHit> hit = scene_.geometry->intersect(ray);
    // How far the recorded vertex's light was: the mixture's parallax (quadtree fields do not read it).
    if (record && previous_recorded && settings_.guiding_mixture) hit ? record->travel(hit->t) : record->escape();
    if (!hit) {
      for (int index : scene_.infinite_lights) {
        const SampledSpectrum le = lights[size_t(index)]->radiance_escaped(ray.direction, lambda);
        const float pmf =
            previous_specular ? 0.0f : light_sampler.pmf(previous_sampling_point, index, light_sampler.part_of_hit(0));
        // The light's own density of the direction, needed by both weights (a specular bounce needs neither).
        const float pdf_li =
            previous_specular ? 0.0f : lights[size_t(index)]->pdf_li(previous_reference, ray.direction);
        const float pdf = pmf * pdf_li;
        const float s_daylit = previous_daylit_factor > 0.0f
                                   ? previous_daylit_factor * daylight_rays->density(index, previous_position,
                                                                                     previous_geometric_normal,
                                                                                     ray.direction, pdf_li)
                                   : 0.0f;
        add_emission(le, pdf, pmf, *lights[size_t(index)], s_daylit);
      }
      break;
    }

    const Vec3 wo_world = -ray.direction;
    segment_length += hit->t;
    if (daylight_rays && depth == 0) {
      const float u_daylight = sampler.next_1d();
      const Vec2 u_daylight_direction = sampler.next_2d(), u_daylight_aperture = sampler.next_2d();
      daylight_ray = daylight_rays->sample(lambda, u_daylight, u_daylight_direction, u_daylight_aperture);
    }
    if (hit->light >= 0 &&
        !(caustic_state == 2 && settings_.caustic_light_tracing && lights[size_t(hit->light)]->samples_emission())) {
      const Light& light = *lights[size_t(hit->light)];
      const SampledSpectrum le = light.radiance(*hit, wo_world, lambda);
      const int part = light_sampler.part_of_hit(hit->primitive);
      const float pmf = previous_specular ? 0.0f : light_sampler.pmf(previous_sampling_point, hit->light, part);
      const float pdf =
          previous_specular ? 0.0f : pmf * light.pdf_part_li(part, previous_reference, ray.direction, &*hit);
      add_emission(le, pdf, pmf, light);
    }
    if (hit->material < 0) break;
    const Material& material = (*scene_.materials)[size_t(hit->material)];
    // A pane may still be passed at the depth limit: next-event estimation from the last vertex went through it, so
    // BSDF sampling must be able to as well (or the MIS weights would not sum to one).
    const bool may_pass = material.passes_shadow_rays() && passages_since_vertex < kMaxShadowPassages;
    const bool depth_reached = depth - passages >= settings_.max_depth;
    if (depth_reached && !may_pass) break;

    MaterialContext context = MaterialContext::at(*hit, wo_world);
    SurfaceDifferentials footprint{};
    if (differentials) footprint = set_footprint(context, *hit, *differentials);
    context.shading_normal = material.shading_normal(context);  // a normal or bump map's, if any
    const Bsdf bsdf = material.bsdf(context, lambda);
    const BsdfFlags flags = bsdf.flags();
    const ShadingContext shading = shading_context(context, !flags.has_transmission);
    const Vec3 wo = shading.frame.to_local(wo_world);
    if (wo.z == 0.0f) break;

    const LightReference reference{hit->position, shading.geometric_normal};
    // Light from below an opaque surface is dropped (wrong_side below), so the sampler may ignore lights there.
    // The path's wavelengths go with it (bvh-spectral chooses by power at them; the same for every hero rotation,
    // so the per-lane light-choice densities are equal and the MIS sums below hold as written).
    const LightSamplingPoint sampling_point{hit->position, flags.has_transmission ? Vec3{} : shading.geometric_normal,
                                            &lambda};
    const float sum_ratio = sum(pdf_ratio);
    // B's density at this vertex (as y) relative to the path's prefix, per unit p(y, ω): Σ_k R_k at the previous
    // vertex over the hero's density of reaching this one from it, in area measure.
    float daylit_factor = 0.0f;
    if (previous_connects && !may_pass && !material.is_stochastic_mix()) {
      const float area_per_solid_angle =
          std::fabs(dot(hit->geometric_normal, ray.direction)) / (segment_length * segment_length);
      if (area_per_solid_angle > 0.0f && std::isfinite(area_per_solid_angle))
        daylit_factor = previous_sum_ratio / (previous_hero_pdf * area_per_solid_angle);
    }

    // Guided vertices (is_guidable says which): every BSDF density below is the mixture's.
    const bool guidable = guiding_on && is_guidable(flags, may_pass);
    const LeafGuide leaf = guidable ? guide_leaf_at(guiding.field, hit->position, shading.geometric_normal) : LeafGuide{};
    // Built only where a leaf guides: a VertexGuide holds a mixture's 16 lobe slots, which every unguided vertex
    // (all of them with guiding off) would otherwise initialise for nothing.
    std::optional<VertexGuide> guide;
    if (leaf) guide.emplace(leaf, hit->position);
    const GuidedBsdf sampling(bsdf, shading.frame, guide ? &*guide : nullptr, settings_.guiding_probability);

    // Next-event estimation: one light (and part), chosen by the scene's light sampler, or among `candidates` of its
    // choices at a glossy vertex.
    const int candidates = flags.has_glossy ? glossy_candidates : 1;
    const float u_light_choice = sampler.next_1d();
    const Vec2 u_light = sampler.next_2d();
    if (flags.has_non_delta && strategy != DirectLighting::bsdf_only) {
      // f·|cos θi| towards a light; zero below an opaque surface (its light cannot reach the material).
      auto f_cos_towards = [&](Vec3 wi_world) {
        if (!flags.has_transmission && dot(wi_world, shading.geometric_normal) <= 0.0f) return SampledSpectrum(0.0f);
        const Vec3 wi = shading.frame.to_local(wi_world);
        return bsdf.eval(wo, wi) * Float4(std::fabs(wi.z));
      };
      // Where the light is chosen among M candidates, the MIS weights count the light sampler's density M times,
      // here and where BSDF sampling hits a light (previous_light_boost): resampling draws the lights that matter
      // here up to M times as often as the sampler alone, and the power heuristic with the sampler's density alone
      // gave BSDF sampling the weight of directions that next-event estimation now serves better. Any factor keeps
      // the estimate unbiased as long as both techniques use the same one (the weights still sum to one), and the
      // resampling targets the weight it will carry. A point with a single light to give does not resample (its
      // choice probability is 1): there the density counts once, on both sides.
      const float boost = float(candidates);
      // The daylit-point technique's density of a light sample's path (0 unless it is a daylight source's, reached
      // from a vertex that connected).
      auto daylit_density = [&](const LightSample& ls, int light_index) {
        return daylit_factor > 0.0f ? daylit_factor * daylight_rays->density(light_index, hit->position,
                                                                             hit->geometric_normal, ls.wi,
                                                                             ls.pdf_solid_angle)
                                    : 0.0f;
      };
      // The MIS weight a light sample will carry (before panes): resampling targets f·L times it.
      auto light_weight = [&](const LightSample& ls, float choice_probability) {
        if (ls.is_delta || strategy == DirectLighting::nee_only) return 1.0f;
        const float s_light = boost * choice_probability * ls.pdf_solid_angle * sum_ratio;
        const float s_bsdf = sum(pdf_ratio * lanes.densities(sampling.pdf(wo, shading.frame.to_local(ls.wi))));
        return s_light * s_light / (s_light * s_light + s_bsdf * s_bsdf);
      };
      if (const auto chosen = choose_light(light_sampler, lights, sampling_point, reference, lambda, candidates,
                                           u_light_choice, u_light, f_cos_towards, light_weight)) {
        const Light& light = *lights[size_t(chosen->pick.light)];
        LightSample ls = chosen->sample;
        Ray shadow;
        shadow.time = ray.time;
        shadow.origin = offset_ray_origin(*hit, ls.wi, scene_.scene_scale);
        const ShadowSegment segment = shadow_segment(shadow.origin, hit->position, ls, scene_.scene_scale);
        shadow.direction = segment.direction;
        shadow.t_max = std::isinf(segment.length) ? segment.length : segment.length * (1.0f - 0x1p-12f);
        if (const auto passage = trace_shadow(scene_, shadow, lambda)) {
          // The MIS weights use the light sampler's own density of this sample, times the boost where the light
          // was resampled (BSDF-sampled hits on the light use the same), so they still sum to one; resampling
          // changes how often the light is drawn, which density_scale accounts for (exactly 1 for one candidate).
          const float s_light = chosen->pick.probability * ls.pdf_solid_angle * sum_ratio;
          // BSDF sampling reaches this light through the panes only by also choosing each one's straight-through
          // lobe: its density carries their probabilities (docs/transport.md, "Glazing").
          const float s_bsdf =
              ls.is_delta || strategy == DirectLighting::nee_only
                  ? 0.0f
                  : sum(pdf_ratio * lanes.densities(sampling.pdf(wo, shading.frame.to_local(ls.wi)) *
                                                    passage->pass_probability));
          // m = (b·s_light)² / ((b·s_light)² + s_bsdf²) over the sampler's density s_light, b the boost above.
          const float b_light = chosen->resampled ? boost * s_light : s_light;
          const float s_daylit = daylit_density(ls, chosen->pick.light);
          const float weight = chosen->density_scale * (b_light / s_light) * b_light /
                               (b_light * b_light + s_bsdf * s_bsdf + s_daylit * s_daylit);
          light.resolve_radiance(ls, lambda);  // pending until the shadow ray passed
          contribute(beta * chosen->f_cos * passage->transmittance * ls.radiance * Float4(kLanes * weight), light);
        }
      }
    }

    // Daylit points: connect this vertex to the point the path's daylight ray lit, where the next vertex would still
    // do next-event estimation (so that the techniques cover the same paths).
    const bool connects = daylight_rays && flags.has_non_delta && !may_pass && depth - passages + 1 < settings_.max_depth;
    if (connects) {
      if (!daylit_traced) {
        daylit_traced = true;
        if (daylight_ray)
          daylit = find_daylit_point(scene_, *daylight_rays, settings_, lambda, *daylight_ray, ray.time, guiding.field);
      }
      if (daylit) {
        const ConnectingVertex x{*hit, shading.frame, shading.geometric_normal, wo, bsdf, sampling,
                                 flags.has_transmission, pdf_ratio, ray.time};
        const SampledSpectrum c =
            connect_to_daylit_point(scene_, lanes, x, *daylit, lambda, settings_.guiding_probability);
        if (max_lane(c) > 0.0f) contribute(beta * c, *lights[size_t(daylit->light)]);
      }
    }

    // BSDF sampling continues the path.
    const float u_lobe = sampler.next_1d();
    const Vec2 u_direction = sampler.next_2d();
    const std::optional<BsdfSample> bs = sampling.sample(wo, u_lobe, u_direction);
    if (!bs || !(bs->pdf[0] > 0.0f)) break;
    const Vec3 wi_world = shading.frame.to_world(bs->wi);
    // Opaque materials: the sampled direction must leave on the geometric front side (shading normals can lie).
    if (!flags.has_transmission && dot(wi_world, shading.geometric_normal) <= 0.0f) break;

    // A pane passed straight through is no vertex for MIS: the segment from the last vertex continues, and the
    // BSDF technique's density of reaching a light along it gains this lobe's probability (the light technique,
    // whose shadow rays pass panes deterministically, is unchanged).
    if (may_pass && bs->wi.z * wo.z < 0.0f) {
      const SampledSpectrum pass_densities = lanes.densities(bs->pdf);
      previous_bsdf_sum = previous_hero_pdf * sum(pdf_ratio * pass_densities);
      previous_hero_pdf *= bs->pdf[0];
      beta *= bs->f * Float4(std::fabs(bs->wi.z) / bs->pdf[0]);
      eta_scale *= bs->eta * bs->eta;
      pdf_ratio *= pass_densities / Float4(bs->pdf[0]);
      ++passages_since_vertex;
      ++passages;
      sampler.next_1d();  // Russian roulette's dimension: a pane is no bounce, so no roulette here
      if (max_lane(abs(beta)) == 0.0f) break;
      // The same line as before the pane (wi = −wo exactly; the frame's round trip would perturb it by an ulp).
      ray.origin = offset_ray_origin(*hit, ray.direction, scene_.scene_scale);
      ray.t_min = 0.0f;
      ray.t_max = INFINITY;
      continue;
    }
    if (depth_reached) break;
    if (!start && depth == passages) caustic_state = bs->is_delta ? 0 : 1;  // the camera ray's first vertex
    else if (caustic_state != 0) caustic_state = bs->is_delta ? 2 : 0;
    passages_since_vertex = 0;
    segment_length = 0.0f;
    previous_connects = connects && !bs->is_delta;
    previous_daylit_factor = daylit_factor;
    previous_position = hit->position;
    previous_geometric_normal = hit->geometric_normal;
    if (differentials)
      differentials = footprint_after_bounce(*differentials, footprint, hit->position, shading.frame.n, wo, bs->wi,
                                             bs->is_delta);

    previous_specular = bs->is_delta;
    previous_hero_pdf = bs->pdf[0];
    previous_sum_ratio = sum_ratio;
    const SampledSpectrum bsdf_densities = lanes.densities(bs->pdf);
    previous_bsdf_sum = sum(pdf_ratio * bsdf_densities);
    previous_reference = reference;
    previous_sampling_point = sampling_point;
    previous_light_boost = float(candidates);  // (BSDF-only: unused, every light density is 0 there)

    beta *= bs->f * Float4(std::fabs(bs->wi.z) / bs->pdf[0]);
    eta_scale *= bs->eta * bs->eta;
    pdf_ratio *= bsdf_densities / Float4(bs->pdf[0]);
    lanes.keep_followed_lanes(bs->wavelength_dependent_direction, pdf_ratio, beta);

    // The vertex's throughput before roulette: what arrives along wi_world, divided by it, is the incident radiance.
    previous_recorded =
        record && guidable &&
        record->add_vertex(hit->position, facing_of(shading.geometric_normal), wi_world, bs->pdf[0],
                           std::fabs(dot(wi_world, shading.geometric_normal)), beta);

    // Russian roulette on the effective throughput (what the film will see), after a few bounces. Radiance
    // scaling inside a denser medium is no loss (it is regained on leaving), so it does not count: without
    // eta_scale, a path inside glass of n = 1.5 would be ended 2.25× as often (pbrt-v4's etaScale).
    const float u_roulette = sampler.next_1d();
    if (depth + 1 >= settings_.russian_roulette_depth) {
      const float effective = max_lane(beta) * eta_scale * kLanes / sum(pdf_ratio);
      const float survive = std::fmin(1.0f, effective);
      if (!(survive > 0.0f) || u_roulette >= survive) break;
      beta /= Float4(survive);
    }
    if (max_lane(abs(beta)) == 0.0f) break;

    ray.origin = offset_ray_origin(*hit, wi_world, scene_.scene_scale);
    ray.direction = wi_world;
    ray.t_min = 0.0f;
    ray.t_max = INFINITY;
  }
  if (record) record->flush(*guiding.record);
  if (!single) return radiance;
  const Float4 hero_only(1.0f, 0.0f, 0.0f, 0.0f);
  if constexpr (kGrouped) groups.mask(hero_only);
  return radiance * hero_only;
}

}  // namespace

SampledSpectrum PathIntegrator::radiance(const Ray& camera_ray, const RayDifferentials* differentials,
                                         const SampledWavelengths& lambda, Sampler& sampler,
                                         const PathGuidingContext& guiding, const LightGroupRadiance& groups) const {
  if (groups.groups)
    return trace_path<true>(scene_, settings_, camera_ray, differentials, lambda, sampler, guiding, nullptr, groups);
  return trace_path<false>(scene_, settings_, camera_ray, differentials, lambda, sampler, guiding, nullptr, groups);
}

SampledSpectrum radiance_from_vertex(const TransportScene& scene, const PathIntegratorSettings& settings, const Ray& ray,
                                     const SampledWavelengths& lambda, Sampler& sampler, const PathStartVertex& start) {
  PathIntegratorSettings unguided = settings;
  unguided.guiding = false;
  return trace_path<false>(scene, unguided, ray, nullptr, lambda, sampler, PathGuidingContext{}, &start,
                           LightGroupRadiance{});
}

}  // namespace rimu
