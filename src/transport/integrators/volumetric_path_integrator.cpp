#include "transport/integrators/volumetric_path_integrator.h"

#include <cmath>

#include "transport/geometry/frame.h"
#include "transport/guiding/guided_bsdf.h"
#include "transport/guiding/path_guiding_record.h"
#include "transport/integrators/light_resampling.h"
#include "transport/integrators/path_footprint.h"
#include "transport/integrators/shadow_passage.h"

namespace rimu {
namespace {

// Crossing more index-matched boundaries than this along one segment means broken geometry (a ray stuck on a
// surface): the segment is then treated as blocked rather than looping.
constexpr int kMaxCrossings = 256;

// What scatters light at a path vertex: a BSDF in its shading frame, or a medium's phase function.
struct Scatterer {
  std::optional<Bsdf> bsdf;  // surface vertex
  Frame frame{};
  Vec3 wo_local{}, wo_world{};
  Vec3 geometric_normal{};  // surface only, on the side of the shading normal
  const HenyeyGreenstein* phase = nullptr;  // medium vertex
  /// Path guiding at a surface vertex (guided_bsdf.h): the learned directions, drawn with probability `alpha`. Every
  /// density below is then the mixture's, as in the surface integrator.
  std::optional<VertexGuide> guide;
  float alpha = 0.0f;
  /// Guiding is on and this surface vertex could be guided: its facing_of (guiding_field.h), −1 elsewhere. Such a
  /// vertex's density is needed now, for the field's record.
  int guided_facing = -1;

  bool has_non_delta() const { return phase || bsdf->flags().has_non_delta; }
  bool opaque() const { return !phase && !bsdf->flags().has_transmission; }
  /// f·|cos θi| (surfaces) or the phase function (media), per lane.
  SampledSpectrum eval(Vec3 wi_world) const {
    if (phase) return Float4(phase->eval(wo_world, wi_world));
    const Vec3 wi = frame.to_local(wi_world);
    return bsdf->eval(wo_local, wi) * Float4(std::fabs(wi.z));
  }
  SampledSpectrum pdf(Vec3 wi_world) const {
    if (phase) return Float4(phase->eval(wo_world, wi_world));
    if (guide) return GuidedBsdf(*bsdf, frame, &*guide, alpha).pdf(wo_local, frame.to_local(wi_world));
    return bsdf->pdf(wo_local, frame.to_local(wi_world));
  }
};

struct DirectionSample {
  Vec3 wi_world;
  SampledSpectrum f_cos;  // f·|cos θi| or phase
  SampledSpectrum pdf;
  bool is_delta = false;
  bool wavelength_dependent_direction = false;  // a dispersive refraction: only the hero can follow it
  float eta = 1.0f;                              // BsdfSample::eta (1 for a phase function)
  bool density_deferred = false;                 // BsdfSample::density_deferred: pdf holds 1, the density is
  Vec3 wi_local{};                               // bsdf->pdf(wo_local, wi_local) with the BSDF's own wi
};

// The density of a direction-sampling decision whose BSDF deferred it (Bsdf::sample_deferring_density), kept with
// the BSDF until the path's next segment reaches a light and MIS reads it.
struct DeferredDensity {
  Bsdf bsdf;
  Vec3 wo_local, wi_local;
};

std::optional<DirectionSample> sample_direction(const Scatterer& s, float u_lobe, Vec2 u) {
  if (s.phase) {
    const PhaseSample ps = s.phase->sample(s.wo_world, u);
    return DirectionSample{ps.wi, Float4(ps.pdf_solid_angle), Float4(ps.pdf_solid_angle), false};
  }
  // A guided vertex needs the BSDF's density for the mixture's, and a guidable one for the field's record: nothing
  // is deferred there.
  const std::optional<BsdfSample> bs =
      s.guide                ? GuidedBsdf(*s.bsdf, s.frame, &*s.guide, s.alpha).sample(s.wo_local, u_lobe, u)
      : s.guided_facing >= 0 ? s.bsdf->sample(s.wo_local, u_lobe, u)
                             : s.bsdf->sample_deferring_density(s.wo_local, u_lobe, u);
  if (!bs || !(bs->pdf[0] > 0.0f)) return std::nullopt;
  const Vec3 wi_world = s.frame.to_world(bs->wi);
  if (s.opaque() && dot(wi_world, s.geometric_normal) <= 0.0f) return std::nullopt;
  return DirectionSample{wi_world, bs->f * Float4(std::fabs(bs->wi.z)), bs->pdf, bs->is_delta,
                         bs->wavelength_dependent_direction, bs->eta, bs->density_deferred, bs->wi};
}

}  // namespace

DistanceSampling distance_sampling_for(DistanceSampling requested, WavelengthMode mode) {
  switch (mode) {
    case WavelengthMode::hero:
    case WavelengthMode::single:
      return requested;
    case WavelengthMode::independent:
      return requested == DistanceSampling::spectral_mis ? DistanceSampling::hero_only : requested;
    case WavelengthMode::rgb:
      return requested == DistanceSampling::averaged ? requested : DistanceSampling::spectral_tracking;
  }
  return requested;
}

std::optional<VolumetricPathIntegrator::ShadowResult> VolumetricPathIntegrator::shadow(
    Vec3 origin, Vec3 direction, float distance, float time, MediumStack stack, const SampledWavelengths& lambda,
    SampledSpectrum throughput) const {
  ShadowResult out{Float4(1.0f), Float4(1.0f)};  // the media's part
  ShadowPassage panes;                           // the panes' part (shadow_passage.h)
  const auto passed = [&] {
    return ShadowResult{out.transmittance * panes.transmittance, out.pass_probability * panes.pass_probability};
  };
  const auto& media = *scene_.media;
  float remaining = std::isinf(distance) ? INFINITY : distance * (1.0f - 0x1p-12f);
  // The trackers' numbers for every medium the shadow ray crosses, keyed by the ray: no sampler dimension, as
  // without media (walk_random.h).
  WalkRandom walk(Ray{origin, direction, 0.0f, remaining, time}, remaining);
  for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
    Ray ray{origin, direction, 0.0f, remaining, time};
    const std::optional<SurfaceHit> hit = scene_.surfaces.geometry->intersect(ray);
    const int medium = stack.current(media);
    if (medium >= 0) {
      // A medium reaching infinity (an open mesh) absorbs everything with σ_t > 0; 1e30 m keeps e^{−σd} defined.
      const float end = hit ? hit->t : std::fmin(remaining, 1e30f);
      const SegmentTransmittance tr =
          estimate_transmittance(media[size_t(medium)], ray, end, lambda, settings_.distance, &walk, throughput);
      out.transmittance *= tr.transmittance;
      out.pass_probability *= tr.pass_probability;
      if (max_lane(out.transmittance * panes.transmittance) <= 0.0f) return std::nullopt;
    }
    if (!hit) return passed();
    const MediumBoundary b = boundary(hit->material);
    if (hit->material < 0) return std::nullopt;
    // Not an index-matched boundary: a pane (thin dielectric), passed with its transmittance as the path's
    // straight-through lobe, or the end of the shadow ray.
    if (!b.index_matched &&
        !panes.pass_surface((*scene_.surfaces.materials)[size_t(hit->material)], *hit, direction, lambda))
      return std::nullopt;
    stack.cross(b.interior_medium, dot(direction, hit->geometric_normal) < 0.0f);
    origin = offset_ray_origin(*hit, direction, scene_.surfaces.scene_scale);
    remaining -= hit->t;
    if (!(remaining > 0.0f)) return passed();
  }
  return std::nullopt;
}

SampledSpectrum VolumetricPathIntegrator::radiance(const Ray& camera_ray, const RayDifferentials* camera_differentials,
                                                   const SampledWavelengths& lambda, Sampler& sampler,
                                                   const PathGuidingContext& guiding,
                                                   const LightGroupRadiance& groups) const {
  const TransportScene& surfaces = scene_.surfaces;
  const auto& lights = *surfaces.lights;
  const auto& media = *scene_.media;
  const LightSampler& light_sampler = *surfaces.light_sampler;
  const PathIntegratorSettings& path = settings_.path;
  const DirectLighting strategy = path.direct_lighting;
  const int glossy_candidates = path.glossy_candidates_for(lights.size());

  SampledSpectrum radiance(0.0f);
  // How each decision's per-lane densities enter (transport/sampling/wavelength_modes.h); free flights follow the mode
  // through settings_.distance (distance_sampling_for).
  const LaneTechniques lanes{path.wavelengths};
  const bool single = path.wavelengths == WavelengthMode::single;
  SampledSpectrum pdf_ratio = lanes.initial_ratios();
  SampledSpectrum beta = pdf_ratio;
  float eta_scale = 1.0f;  // Π η'² over the refractions: beta × eta_scale has no radiance scaling (BsdfSample::eta)
  Ray ray = camera_ray;
  std::optional<RayDifferentials> differentials;
  if (surfaces.texture_footprints && camera_differentials) differentials = *camera_differentials;
  MediumStack stack;
  stack.cross(scene_.camera_medium, true);  // −1: the camera is in vacuum

  // MIS state of the last direction-sampling decision (see docs/media.md, "Lights reached by direction sampling").
  bool previous_specular = true;
  float previous_hero_pdf = 1.0f;      // q_dir,0 (unless deferred: then previous_density's)
  std::optional<DeferredDensity> previous_density;  // the last decision's density, not yet evaluated
  float previous_sum_ratio = 4.0f;     // Σ R_k before the direction decision
  float pass_product = 1.0f;           // the technique's probability of passing the free flights since then
  LightReference previous_reference{};
  LightSamplingPoint previous_sampling_point{};

  // Path guiding (path_integrator.cpp says what is learned): this path's record, if it teaches the field.
  std::optional<PathGuidingRecord> record;
  if (path.guiding && guiding.record && guiding.record->size() < guiding.record_limit)
    record.emplace(guiding_lane_weights(lambda, path.wavelengths == WavelengthMode::rgb));
  bool previous_recorded = false;  // the last direction decision's vertex is the record's last one
  // The last vertex, if it scattered on a segment where the equiangular technique ran: an emitter its sampled
  // direction reaches is the distance technique's estimate too, and takes w_d (volumetric_equiangular.cpp).
  struct EquiangularVertex {
    EquiangularSegment segment;
    int medium = -1;
    float t = 0.0f;
    SampledSpectrum ratios_before_flight;
  };
  std::optional<EquiangularVertex> previous_equiangular;

  // Every emitted contribution, credited to its light's group as well (light_group_radiance.h). `direct_by_mis`:
  // an emitter the last vertex's own sampled direction reached, weighted against next-event estimation there, which
  // that vertex does not learn (as in the surface integrator).
  auto contribute = [&](const SampledSpectrum& contribution, int light_group, bool direct_by_mis = false) {
    radiance += contribution;
    groups.add(light_group, contribution);
    if (record) record->add_radiance(contribution, direct_by_mis && previous_recorded);
  };
  auto add_emission = [&](const SampledSpectrum& emitted, float light_pdf_solid_angle, const Light& light) {
    if (strategy == DirectLighting::nee_only && !previous_specular) return;
    if (strategy == DirectLighting::bsdf_only) light_pdf_solid_angle = 0.0f;
    const float sum_ratio = sum(pdf_ratio);
    if (!(sum_ratio > 0.0f)) return;
    if (previous_specular || light_pdf_solid_angle <= 0.0f) {
      contribute(beta * emitted * Float4(kLanes / sum_ratio), light.light_group());
      return;
    }
    // S_dir = q_dir,0 · pass · Σ R_k (R already holds the direction and pass ratios); S_light = q_light · Σ R_before.
    if (previous_density) {  // evaluated once, where a light is reached (its R_k ratios were 1: equal in all lanes)
      previous_hero_pdf = previous_density->bsdf.pdf(previous_density->wo_local, previous_density->wi_local)[0];
      previous_density.reset();
    }
    // sample() drops a direction whose density is not positive and finite; a deferred one is dropped here.
    if (!(previous_hero_pdf > 0.0f) || !std::isfinite(previous_hero_pdf)) return;
    const float scale = previous_hero_pdf * pass_product;
    const float s_dir = scale * sum_ratio;
    const float s_light = light_pdf_solid_angle * previous_sum_ratio;
    contribute(beta * emitted * Float4(kLanes * scale * s_dir / (s_light * s_light + s_dir * s_dir)),
               light.light_group(), true);
  };

  int surface_depth = 0, vertex_count = 0, medium_events = 0, crossings = 0;
  int depth_medium_events = 0;  // the medium events that count towards max_depth (Medium::counts_towards_max_depth)
  int passages_since_vertex = 0;  // panes passed straight through since the last vertex (≤ kMaxShadowPassages)
  // A textured subsurface albedo (TexturedAlbedo): the factor on σ_s read where the path last entered that medium.
  struct AlbedoScale {
    int medium = -1;
    SampledSpectrum scale{1.0f};
  };
  AlbedoScale walk_albedo;
  for (;;) {
    std::optional<AlbedoScale> entry_albedo;  // set at a surface whose enclosed medium has a textured albedo
    const std::optional<SurfaceHit> hit = surfaces.geometry->intersect(ray);
    const float t_surface = hit ? hit->t : INFINITY;

    // Free flight through the current medium up to the surface.
    std::optional<Vec3> scatter_point;
    std::optional<EquiangularSegment> equiangular;  // set when the equiangular technique ran on this segment
    const SampledSpectrum ratios_before_flight = pdf_ratio;
    float flight_t = 0.0f;
    const int medium_index = stack.current(media);
    // The depth the next vertex would have; a medium vertex that reaches max_depth ends the path before its NEE.
    const int depth = surface_depth + (settings_.max_depth_includes_media ? depth_medium_events : 0);
    // Inside a subsurface walk (Medium::counts_towards_max_depth false) every vertex, in the medium or on its
    // boundary seen from inside, belongs to the surface vertex where the path entered, which max_depth allowed: as
    // pbrt-v4 spends one bounce on a BSSRDF, internal reflections included. Russian roulette and
    // max_medium_events bound the walk.
    const bool in_walk = medium_index >= 0 && !media[size_t(medium_index)].counts_towards_max_depth();
    if (medium_index >= 0) {
      const Medium& medium = media[size_t(medium_index)];
      // The equiangular technique is NEE from this segment's scattering points: none when those would end the path.
      const bool medium_vertex_allowed = !settings_.max_depth_includes_media || in_walk || depth < path.max_depth;
      // Not inside a subsurface walk: its lights lie beyond the refracting boundary, which blocks the connection.
      if (medium_vertex_allowed && !in_walk && uses_equiangular(medium)) {
        equiangular =
            EquiangularSegment{ray.origin, ray.direction, ray.t_min, std::fmin(t_surface, 1e30f), {}, ray.time};
        int light_group = 0;
        SampledSpectrum direct =
            equiangular_direct(*equiangular, medium, beta, pdf_ratio, stack, lambda, sampler, light_group);
        if (walk_albedo.medium == medium_index) direct *= walk_albedo.scale;
        contribute(direct, light_group);
      }
      if (medium.emission()) {
        // The light the medium emits along this segment, seen from the last vertex: an estimator of its own
        // (emitted_along), counted as surface emission at the segment's end is, with no light sampling to weigh
        // it against (emissive media are not light-sampled).
        const float sum_ratio = sum(pdf_ratio);
        if (sum_ratio > 0.0f)
          contribute(beta * emitted_along(medium, ray, std::fmin(t_surface, 1e30f), lambda, sampler) *
                         Float4(kLanes / sum_ratio),
                     medium.emission_light_group());
      }
      SampledSpectrum throughput = beta;  // β ∝ the effective throughput while R is lane-independent
      const FreeFlight flight = sample_free_flight(media[size_t(medium_index)], ray, std::fmin(t_surface, 1e30f),
                                                   lambda, settings_.distance, sampler, throughput);
      beta *= flight.weight;
      pdf_ratio *= flight.pdf_ratio;
      if (flight.terminated()) break;
      if (flight.scattered) {
        flight_t = flight.t;
        scatter_point = ray.origin + ray.direction * flight.t;
        if (walk_albedo.medium == medium_index) beta *= walk_albedo.scale;
      } else {
        pass_product *= flight.pass_probability;
      }
    }

    Scatterer scatterer;
    SurfaceDifferentials footprint{};  // at a surface vertex reached with differentials
    LightReference reference;
    Vec3 shadow_origin;
    // A pane (Material::passes_shadow_rays) may be passed straight through: then it is no vertex (see path_integrator.cpp).
    bool may_pass = false, depth_reached = false;
    if (scatter_point) {
      if (settings_.max_depth_includes_media && !in_walk && depth >= path.max_depth) break;
      if (++medium_events > settings_.max_medium_events) break;
      if (!in_walk) ++depth_medium_events;
      scatterer.phase = &media[size_t(medium_index)].phase();
      scatterer.wo_world = -ray.direction;
      reference = {*scatter_point, Vec3{}};
      shadow_origin = *scatter_point;
    } else {
      if (!hit) {
        for (int index : surfaces.infinite_lights) {
          const SampledSpectrum le = lights[size_t(index)]->radiance_escaped(ray.direction, lambda);
          const float pdf = previous_specular ? 0.0f
                                              : light_sampler.pmf(previous_sampling_point, index, light_sampler.part_of_hit(0)) *
                                                    lights[size_t(index)]->pdf_li(previous_reference, ray.direction);
          add_emission(le, pdf, *lights[size_t(index)]);
        }
        break;
      }
      if (hit->light >= 0) {
        const Light& light = *lights[size_t(hit->light)];
        const int part = light_sampler.part_of_hit(hit->primitive);
        // (A medium vertex, the only one with an equiangular state, is never specular.)
        const float choice = previous_specular ? 0.0f : light_sampler.pmf(previous_sampling_point, hit->light, part);
        const float pdf =
            previous_specular ? 0.0f : choice * light.pdf_part_li(part, previous_reference, ray.direction, &*hit);
        float equiangular_weight = 1.0f;  // w_d, when the last vertex scattered where equiangular sampling ran
        if (previous_equiangular)
          if (const auto centre_m = equiangular_centre_m(light, part))
            equiangular_weight = distance_technique_weight(
                previous_equiangular->segment, media[size_t(previous_equiangular->medium)], previous_equiangular->t,
                *centre_m, previous_equiangular->ratios_before_flight, lambda, choice,
                light_sampler.pmf(equiangular_choice_point(previous_equiangular->segment), hit->light, part));
        add_emission(light.radiance(*hit, -ray.direction, lambda) * Float4(equiangular_weight), pdf, light);
      }
      const MediumBoundary b = boundary(hit->material);
      if (b.index_matched) {
        // No BSDF: the ray continues unchanged into (or out of) the enclosed medium; no vertex, no MIS change.
        if (++crossings > kMaxCrossings * 64) break;
        stack.cross(b.interior_medium, dot(ray.direction, hit->geometric_normal) < 0.0f);
        ray.origin = offset_ray_origin(*hit, ray.direction, surfaces.scene_scale);
        ray.t_min = 0.0f;
        ray.t_max = INFINITY;
        continue;
      }
      if (hit->material < 0) break;
      const Material& material = (*surfaces.materials)[size_t(hit->material)];
      may_pass = material.passes_shadow_rays() && passages_since_vertex < kMaxShadowPassages;
      if (in_walk) {
        // A boundary reached from inside the walk: no depth of its own (above); bounded like the walk's events.
        if (++medium_events > settings_.max_medium_events) break;
      } else {
        depth_reached = depth >= path.max_depth;
        if (depth_reached && !may_pass) break;
        ++surface_depth;
      }
      MaterialContext context = MaterialContext::at(*hit, -ray.direction);
      if (differentials) footprint = set_footprint(context, *hit, *differentials);
      if (const int inside = boundary(hit->material).interior_medium;
          inside >= 0 && dot(ray.direction, hit->geometric_normal) < 0.0f)
        if (const TexturedAlbedo* albedo = media[size_t(inside)].textured_albedo())
          entry_albedo = AlbedoScale{inside, albedo->scattering_scale(context, lambda)};
      context.shading_normal = material.shading_normal(context);  // a normal or bump map's, if any
      scatterer.bsdf = material.bsdf(context, lambda);
      const bool two_sided = !scatterer.bsdf->flags().has_transmission;
      Vec3 ns = context.shading_normal, ng = hit->geometric_normal;
      if (two_sided && dot(ray.direction, ng) > 0.0f) {
        ns = -ns;
        ng = -ng;
      }
      scatterer.frame = Frame::from_normal(ns);
      scatterer.geometric_normal = ng;
      scatterer.wo_world = -ray.direction;
      scatterer.wo_local = scatterer.frame.to_local(scatterer.wo_world);
      if (scatterer.wo_local.z == 0.0f) break;
      // Guided as the surface integrator guides (is_guidable): the same field and facing.
      const BsdfFlags flags = scatterer.bsdf->flags();
      if (path.guiding && is_guidable(flags, may_pass)) {
        scatterer.guided_facing = facing_of(ng);
        if (const LeafGuide leaf = guide_leaf_at(guiding.field, hit->position, ng)) {
          scatterer.guide.emplace(leaf, hit->position);
          scatterer.alpha = path.guiding_probability;
        }
      }
      reference = {hit->position, ng};
      shadow_origin = hit->position;
    }
    ++vertex_count;
    // Light from below an opaque surface is dropped (wrong_side below), so the sampler may ignore lights there.
    // With the path's wavelengths (bvh-spectral; path_integrator.cpp says why the MIS needs no change).
    const LightSamplingPoint sampling_point{reference.position, scatterer.opaque() ? reference.normal : Vec3{},
                                            &lambda};

    // Rescale β and R together so that Σ R = 4 (the lane estimates 4β/ΣR do not change). Not at a pane that may be
    // passed: the MIS state of the last vertex, which add_emission still uses then, is in the unscaled units.
    if (!may_pass) {
      const float rescale = kLanes / sum(pdf_ratio);
      if (!(rescale > 0.0f) || !std::isfinite(rescale)) break;
      beta *= Float4(rescale);
      pdf_ratio *= Float4(rescale);
    }
    const float sum_ratio = may_pass ? sum(pdf_ratio) : kLanes;

    // The medium stack on the side a direction leaves into (surfaces with transmission may cross).
    auto stack_towards = [&](Vec3 wi_world) {
      MediumStack s = stack;
      if (!scatter_point && dot(wi_world, hit->geometric_normal) * dot(-ray.direction, hit->geometric_normal) < 0.0f)
        s.cross(boundary(hit->material).interior_medium, dot(wi_world, hit->geometric_normal) < 0.0f);
      return s;
    };
    auto origin_towards = [&](Vec3 wi_world) {
      return scatter_point ? shadow_origin
                           : offset_ray_origin(*hit, wi_world, surfaces.scene_scale);
    };

    // Next-event estimation with transmittance.
    const float u_light_choice = sampler.next_1d();
    const Vec2 u_light = sampler.next_2d();
    if (scatterer.has_non_delta() && strategy != DirectLighting::bsdf_only) {
      // The light: the sampler's choice, or at a glossy surface one of several candidates resampled by what the BSDF
      // passes from each (light_resampling.h; density_scale is then the factor on the usual estimate). Not at
      // medium vertices. A costly BSDF flagged glossy (a coated metal's random walk) has then been evaluated
      // towards every candidate before any shadow ray: the kept one's f·|cos θi| is reused below (eval() is a
      // deterministic function of the directions, so it is the same value evaluate() would compute again).
      std::optional<LightChoice> pick;
      std::optional<LightSample> ls;
      std::optional<SampledSpectrum> chosen_f;
      float density_scale = 1.0f;
      if (glossy_candidates > 1 && scatterer.bsdf && scatterer.bsdf->flags().has_glossy) {
        auto f_cos_towards = [&](Vec3 wi_world) {
          if (scatterer.opaque() && dot(wi_world, scatterer.geometric_normal) <= 0.0f) return SampledSpectrum(0.0f);
          return scatterer.eval(wi_world);
        };
        auto light_weight = [&](const LightSample& candidate, float choice_probability) {
          if (candidate.is_delta || strategy == DirectLighting::nee_only) return 1.0f;
          const float s_light = choice_probability * candidate.pdf_solid_angle * sum_ratio;
          const float s_dir = sum(pdf_ratio * lanes.densities(scatterer.pdf(candidate.wi)));
          return s_light * s_light / (s_light * s_light + s_dir * s_dir);
        };
        if (const auto chosen = choose_light(light_sampler, lights, sampling_point, reference, lambda, glossy_candidates,
                                             u_light_choice, u_light, f_cos_towards, light_weight)) {
          pick = chosen->pick;
          ls = chosen->sample;
          chosen_f = chosen->f_cos;
          density_scale = chosen->density_scale;
        }
      } else if ((pick = light_sampler.sample(sampling_point, u_light_choice))) {
        ls = lights[size_t(pick->light)]->sample_part_li_deferred(pick->part, reference, lambda, u_light);
      }
      if (pick && ls) {
        const Light& light = *lights[size_t(pick->light)];
        // f·|cos θi| towards the light, the direction technique's densities q_k there, and the effective
        // throughput direction sampling would have had towards wi: 4·β·f / Σ_k R_k q_k(wi). None where f = 0.
        struct Towards {
          SampledSpectrum f, q_dir, throughput;
        };
        auto evaluate = [&]() -> std::optional<Towards> {
          const SampledSpectrum f = chosen_f ? *chosen_f : scatterer.eval(ls->wi);
          if (!(max_lane(f) > 0.0f)) return std::nullopt;
          const SampledSpectrum q_dir = lanes.densities(scatterer.pdf(ls->wi));
          const float sum_dir = sum(pdf_ratio * q_dir);
          return Towards{f, q_dir, sum_dir > 0.0f ? beta * f * Float4(kLanes / sum_dir) : beta * f};
        };
        const bool wrong_side = scatterer.opaque() && dot(ls->wi, scatterer.geometric_normal) <= 0.0f;
        // A costly BSDF is evaluated only if the light is visible, unless the shadow ray needs the throughput
        // (tracked media). Same estimate either way: shadow() draws no sampler numbers.
        const bool visibility_first =
            scatterer.bsdf && scatterer.bsdf->evaluation_is_costly() && !shadow_reads_throughput_;
        std::optional<Towards> towards;
        if (!wrong_side && !visibility_first) towards = evaluate();
        if (!wrong_side && (visibility_first || towards)) {
          const Vec3 origin = origin_towards(ls->wi);
          const ShadowSegment segment = shadow_segment(origin, reference.position, *ls, surfaces.scene_scale);
          const auto tr = shadow(origin, segment.direction, segment.length, ray.time, stack_towards(ls->wi), lambda,
                                 towards ? towards->throughput : beta);  // β: read by tracked media only
          if (tr && visibility_first) towards = evaluate();
          if (tr && towards) {
            const SampledSpectrum& f = towards->f;
            const SampledSpectrum& q_dir = towards->q_dir;
            const float s_light = pick->probability * ls->pdf_solid_angle * sum_ratio;
            const float s_dir = ls->is_delta || strategy == DirectLighting::nee_only
                                    ? 0.0f
                                    : sum(pdf_ratio * q_dir * tr->pass_probability);
            float weight = density_scale * s_light / (s_light * s_light + s_dir * s_dir);
            if (equiangular && scatter_point)
              if (const auto centre_m = equiangular_centre_m(light, pick->part))
                weight *= distance_technique_weight(*equiangular, media[size_t(medium_index)], flight_t, *centre_m,
                                                    ratios_before_flight, lambda,
                                                    pick->probability, light_sampler.pmf(equiangular_choice_point(*equiangular),
                                                                                         pick->light, pick->part));
            light.resolve_radiance(*ls, lambda);  // pending until the shadow ray passed
            contribute(beta * f * tr->transmittance * ls->radiance * Float4(kLanes * weight), light.light_group());
          }
        }
      }
    }

    // Direction sampling continues the path.
    const float u_lobe = sampler.next_1d();
    const Vec2 u_direction = sampler.next_2d();
    const std::optional<DirectionSample> ds = sample_direction(scatterer, u_lobe, u_direction);
    if (!ds) break;
    if (may_pass && dot(ds->wi_world, hit->geometric_normal) * dot(ray.direction, hit->geometric_normal) > 0.0f) {
      // Straight through the pane: the segment from the last vertex goes on, its direction technique's pass
      // probability times this lobe's (as a free flight passed; docs/transport.md, "Glazing").
      pass_product *= ds->pdf[0];
      beta *= ds->f_cos / Float4(ds->pdf[0]);
      eta_scale *= ds->eta * ds->eta;
      pdf_ratio *= lanes.densities(ds->pdf) / Float4(ds->pdf[0]);
      if (!in_walk) --surface_depth;
      --vertex_count;
      ++passages_since_vertex;
      sampler.next_1d();  // Russian roulette's dimension: no roulette at a pane
      if (max_lane(abs(beta)) == 0.0f) break;
      // The same line as before the pane (wi = −wo exactly; the frame's round trip would perturb it by an ulp).
      const MediumStack next_stack = stack_towards(ray.direction);
      ray.origin = origin_towards(ray.direction);
      stack = next_stack;
      ray.t_min = 0.0f;
      ray.t_max = INFINITY;
      continue;
    }
    if (depth_reached) break;
    passages_since_vertex = 0;
    if (differentials)
      differentials = scatter_point ? std::nullopt
                                    : footprint_after_bounce(*differentials, footprint, hit->position, scatterer.frame.n,
                                                             scatterer.wo_local, scatterer.frame.to_local(ds->wi_world),
                                                             ds->is_delta);
    previous_specular = ds->is_delta;
    previous_equiangular.reset();
    if (scatter_point && equiangular)
      previous_equiangular = EquiangularVertex{*equiangular, medium_index, flight_t, ratios_before_flight};
    previous_hero_pdf = ds->pdf[0];
    previous_density.reset();
    if (ds->density_deferred) previous_density.emplace(DeferredDensity{*scatterer.bsdf, scatterer.wo_local, ds->wi_local});
    previous_sum_ratio = sum_ratio;
    pass_product = 1.0f;
    previous_reference = reference;
    previous_sampling_point = sampling_point;
    beta *= ds->f_cos / Float4(ds->pdf[0]);
    eta_scale *= ds->eta * ds->eta;
    pdf_ratio *= lanes.densities(ds->pdf) / Float4(ds->pdf[0]);
    lanes.keep_followed_lanes(ds->wavelength_dependent_direction, pdf_ratio, beta);
    // What arrives along wi, divided by the vertex's effective throughput (4β/ΣR: β alone is rescaled at every
    // vertex), is the incident radiance the record learns. A medium vertex is not recorded.
    previous_recorded = false;
    if (record && scatterer.guided_facing >= 0) {
      const float effective = kLanes / sum(pdf_ratio);
      if (effective > 0.0f && std::isfinite(effective))
        previous_recorded = record->add_vertex(hit->position, scatterer.guided_facing, ds->wi_world, ds->pdf[0],
                                               std::fabs(dot(ds->wi_world, scatterer.geometric_normal)),
                                               beta * Float4(effective));
    }

    const float u_roulette = sampler.next_1d();
    if (vertex_count >= path.russian_roulette_depth) {
      // Radiance scaling is regained on leaving a denser medium: it does not count (pbrt-v4's etaScale).
      const float effective = max_lane(beta) * eta_scale * kLanes / sum(pdf_ratio);
      const float survive = std::fmin(1.0f, effective);
      if (!(survive > 0.0f) || u_roulette >= survive) break;
      beta /= Float4(survive);
    }
    if (max_lane(abs(beta)) == 0.0f) break;

    const MediumStack next_stack = stack_towards(ds->wi_world);
    ray.origin = origin_towards(ds->wi_world);
    stack = next_stack;
    if (entry_albedo && stack.current(media) == entry_albedo->medium) walk_albedo = *entry_albedo;
    ray.direction = ds->wi_world;
    ray.t_min = 0.0f;
    ray.t_max = INFINITY;
  }
  if (record) record->flush(*guiding.record);
  if (!single) return radiance;
  const Float4 hero_only(1.0f, 0.0f, 0.0f, 0.0f);
  if (groups.groups) groups.mask(hero_only);
  return radiance * hero_only;
}

}  // namespace rimu
