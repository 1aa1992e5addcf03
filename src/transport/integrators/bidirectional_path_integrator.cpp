#include "transport/integrators/bidirectional_path_integrator.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "spectral/wavelengths/lanes.h"
#include "transport/geometry/frame.h"
#include "transport/integrators/adjoint_shading.h"
#include "transport/integrators/bidirectional_mis.h"
#include "transport/integrators/daylit_connection.h"
#include "transport/integrators/shadow_passage.h"
#include "transport/lights/daylight_ray_sampler.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {
namespace {

enum class VertexKind : uint8_t {
  camera,             ///< z₀, on the lens
  light,              ///< y₀, or a light sampled by next-event estimation
  light_at_infinity,  ///< where a camera subpath escaped, or a light at infinity sampled by next-event estimation
  surface
};

struct PathVertex {
  VertexKind kind = VertexKind::surface;
  Vec3 position{};
  /// Geometric normal: on a surface, flipped with the shading frame for opaque materials (to the side the subpath
  /// arrived from); on a light, its emitting side's; zero for a lamp at a point and the lens. At infinity: the
  /// direction the camera subpath escaped along.
  Vec3 ng{};
  Frame frame{};
  Vec3 wo{};  ///< local: towards the previous vertex of its own subpath
  std::optional<Bsdf> bsdf;
  bool transmits = false;
  bool pane = false;           ///< a surface subpaths may pass straight through (Material::passes_shadow_rays)
  bool delta = false;          ///< its subpath left it by a delta lobe (no technique can join the path here)
  bool non_delta = false;      ///< its BSDF has a non-delta component (a technique may join the path here)
  SampledSpectrum beta{0.0f};  ///< the subpath's throughput up to this vertex (hero-density units)
  SampledSpectrum ratio{1.0f};  ///< the subpath's spectral-MIS ratios R_h = p_h/p_hero
  SampledSpectrum pdf_fwd{0.0f};  ///< area density of this vertex from the previous one of its subpath
  SampledSpectrum pdf_rev{0.0f};  ///< area density of this vertex from the next one of its subpath
  /// The probability that a walk along the edge from the previous vertex of its subpath passes the panes on it (per
  /// lane, the same either way along it): both walks pass each by choosing its straight-through lobe, so the
  /// edge's densities from either side carry it; shadow rays pass them deterministically (shadow_passage.h).
  SampledSpectrum pass_in{1.0f};
  SurfaceHit hit{};
  // As a light's end of a path (y₀, or a camera subpath's hit on an emitter):
  int light = -1;
  SampledSpectrum emitted{0.0f};  ///< on a camera subpath: L_e towards the previous vertex
  float pdf_nee = 0.0f;   ///< next-event estimation's density of this point from the neighbouring vertex
  float pdf_emit = 0.0f;  ///< the light subpaths' density of this point (choice × p_A; daylight: its choice)
  bool hittable = false;  ///< as y₀: a camera subpath can hit it (an emitting surface, a light at infinity not delta)
  float emit_direction = 0.0f;  ///< on a camera subpath: the light's p_ω towards the previous vertex
  // Random numbers drawn for next-event estimation where the camera subpath reached this vertex (the path
  // tracer's dimension order).
  float u_light_choice = 0.0f;
  Vec2 u_light{};

  /// Whether a technique may join the path at this vertex as an inner vertex of its subpath (not a delta sample).
  bool connectible() const { return !delta && non_delta; }
  Vec3 world(Vec3 local) const { return frame.to_world(local); }
  /// A direction towards which light can leave (or arrive at) an opaque surface: its flipped geometric front.
  bool on_side(Vec3 w) const { return transmits || dot(w, ng) > 0.0f; }
};

// The panes a subpath has passed since its last vertex (PathVertex::pass_in): the product of their
// straight-through lobes' probabilities per lane, and how many (a ninth is a vertex: kMaxShadowPassages).
struct PaneEdge {
  SampledSpectrum pass{1.0f};
  int count = 0;
  bool open() const { return count < kMaxShadowPassages; }
};

// A solid-angle density at `from` of the direction towards `to`, as an area density at `to`: × |cos θ_to|/d² (a
// point without normal: 1/d²). Lights at infinity keep solid-angle densities (every technique reaching them does).
SampledSpectrum to_area(const SampledSpectrum& pdf, Vec3 from, Vec3 to_position, Vec3 to_normal, bool at_infinity) {
  if (at_infinity) return pdf;
  const Vec3 d = from - to_position;
  const float d2 = length_squared(d);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return SampledSpectrum(0.0f);
  float g = 1.0f / d2;
  if (!(to_normal == Vec3{})) g *= std::fabs(dot(to_normal, d)) / std::sqrt(d2);
  return pdf * Float4(g);
}
SampledSpectrum to_area(const SampledSpectrum& pdf, Vec3 from, const PathVertex& to) {
  return to_area(pdf, from, to.position, to.ng, to.kind == VertexKind::light_at_infinity);
}

}  // namespace

BidirectionalPathIntegrator::BidirectionalPathIntegrator(const TransportScene& scene,
                                                         const PathIntegratorSettings& settings,
                                                         const LightTracingCamera& camera, double film_pixels)
    : scene_(scene), settings_(settings), camera_(camera), film_pixels_(float(std::max(1.0, film_pixels))) {
  std::vector<double> power;
  emission_choice_.assign(scene.lights->size(), 0.0f);
  for (size_t i = 0; i < scene.lights->size(); ++i) {
    const Light& light = *(*scene.lights)[i];
    if (!light.samples_emission()) continue;
    const double p = light.total_power_w(scene.scene_scale);
    if (!(p > 0.0) || !std::isfinite(p)) continue;
    emitting_.push_back(int(i));
    power.push_back(p);
  }
  const bool daylight = scene.daylight_rays && !scene.daylight_rays->empty() &&
                        scene.daylight_rays->total_power_w() > 0.0 && std::isfinite(scene.daylight_rays->total_power_w());
  if (daylight) power.push_back(scene.daylight_rays->total_power_w());
  if (power.empty()) return;
  by_power_.emplace(power);
  for (size_t k = 0; k < emitting_.size(); ++k)
    emission_choice_[size_t(emitting_[k])] = by_power_->probability(int(k));
  if (daylight) daylight_choice_ = by_power_->probability(int(emitting_.size()));
}

namespace {

// Everything one camera sample's subpaths share.
struct Subpaths {
  const TransportScene& scene;
  const PathIntegratorSettings& settings;
  const SampledWavelengths& lambda;
  LaneTechniques lanes;
  float time = 0.0f;
  std::vector<PathVertex>& camera;  // this thread's storage, cleared per camera sample
  std::vector<PathVertex>& light;

  // The vertex a ray hit, with its BSDF in the frame of the side it arrived from (`wo_world` back along the ray).
  bool make_surface_vertex(const SurfaceHit& hit, Vec3 wo_world, PathVertex& v) const {
    v.kind = VertexKind::surface;
    v.position = hit.position;
    v.hit = hit;
    v.ng = hit.geometric_normal;
    if (hit.material < 0) return false;
    const Material& material = (*scene.materials)[size_t(hit.material)];
    // An emitting pane stays a vertex (its emission is the technique s = 0's).
    v.pane = scene.passable_surfaces && material.passes_shadow_rays() && hit.light < 0;
    MaterialContext context = MaterialContext::at(hit, wo_world);
    context.shading_normal = material.shading_normal(context);
    v.bsdf.emplace(material.bsdf(context, lambda));
    const BsdfFlags flags = v.bsdf->flags();
    v.transmits = flags.has_transmission;
    v.non_delta = flags.has_non_delta;
    Vec3 ns = context.shading_normal, ng = hit.geometric_normal;
    if (!flags.has_transmission && dot(wo_world, ng) < 0.0f) {
      ns = -ns;
      ng = -ng;
    }
    v.ng = ng;
    v.frame = Frame::from_normal(ns);
    v.wo = v.frame.to_local(wo_world);
    return v.wo.z != 0.0f;
  }

  // The bookkeeping after the last vertex of `path` drew `bs` (the caller updates the throughput): whether it was a
  // delta sample, the previous vertex's reverse density (of being reached from here), the next vertex's forward
  // density `pdf_direction` (a delta lobe's counts 1, unconverted, on both sides) and the spectral-MIS ratios.
  void record_scattering(std::vector<PathVertex>& path, const BsdfSample& bs, SampledSpectrum& pdf_direction,
                         SampledSpectrum& ratio) const {
    PathVertex& here = path.back();
    PathVertex& before = path[path.size() - 2];
    here.delta = bs.is_delta;
    const SampledSpectrum densities = lanes.densities(bs.pdf);
    before.pdf_rev =
        here.delta ? SampledSpectrum(1.0f)
                   : to_area(lanes.densities(here.bsdf->pdf(bs.wi, here.wo)), here.position, before) * here.pass_in;
    pdf_direction = here.delta ? SampledSpectrum(1.0f) : densities;
    ratio *= densities / Float4(bs.pdf[0]);
  }

  // Whether `bs`, drawn at the pane `v` (hit by `ray` at `hit`), passes straight through it (as the path tracer
  // passes panes): then `v` is no vertex, the edge being walked goes on with the lobe's probability per lane in
  // `edge`, its transmittance over that probability in `beta` (the spectral-MIS ratios as for any sampled lobe),
  // and `ray` continues along the same line from the pane's far side.
  bool passes(const PathVertex& v, const BsdfSample& bs, const SurfaceHit& hit, PaneEdge& edge, SampledSpectrum& beta,
              SampledSpectrum& ratio, Ray& ray) const {
    if (!v.pane || !edge.open() || !(bs.wi.z * v.wo.z < 0.0f)) return false;
    const SampledSpectrum densities = lanes.densities(bs.pdf);
    edge.pass *= densities;
    ++edge.count;
    beta *= bs.f * Float4(std::fabs(bs.wi.z) / bs.pdf[0]);
    ratio *= densities / Float4(bs.pdf[0]);
    ray.origin = offset_ray_origin(hit, ray.direction, scene.scene_scale);
    ray.t_min = 0.0f;
    ray.t_max = INFINITY;
    return true;
  }

  // Russian roulette as the path tracer's: on the effective throughput in units of `unit` (a light subpath's flux
  // at its first vertex: what it carries then is what scattering has left of it, whatever the light's units), once
  // a subpath has `vertices` scattering vertices (the path tracer's depth + 1) and from russian_roulette_depth on.
  bool survives(const SampledSpectrum& beta, const SampledSpectrum& ratio, float eta_scale, float unit, int vertices,
                float u, SampledSpectrum& beta_out) const {
    if (vertices < settings.russian_roulette_depth) return true;
    const float effective = max_lane(beta) / unit * eta_scale * kLanes / sum(ratio);
    const float q = std::fmin(1.0f, effective);
    if (!(q > 0.0f) || u >= q) return false;
    beta_out /= Float4(q);
    return true;
  }

  LightSamplingPoint sampling_point(const PathVertex& v) const {
    return {v.position, v.transmits ? Vec3{} : v.ng, &lambda};
  }

  // Next-event estimation's density (area; solid angle at infinity; the choice alone for a delta light) of the
  // point of `light` at `hit` (nullptr at infinity) seen from `from` along `wi` at distance d.
  float nee_density(const PathVertex& from, int light_index, Vec3 wi, const SurfaceHit* hit) const {
    const Light& light = *(*scene.lights)[size_t(light_index)];
    const LightSampler& sampler = *scene.light_sampler;
    const int part = sampler.part_of_hit(hit ? hit->primitive : 0);
    const float pmf = sampler.pmf(sampling_point(from), light_index, part);
    if (light.is_delta()) return pmf;
    const float pdf = pmf * light.pdf_part_li(part, LightReference{from.position, from.ng}, wi, hit);
    if (!hit) return pdf;
    const float d2 = length_squared(hit->position - from.position);
    if (!(d2 > 0.0f)) return 0.0f;
    return pdf * std::fabs(dot(hit->geometric_normal, wi)) / d2;
  }
};


// Where light subpaths start: the integrator's choice of lights by power.
struct LightStarts {
  const Distribution1D* by_power = nullptr;
  const std::vector<int>& emitting;
};

// The light subpath into p.light: y₀ on a light chosen by power (or a ray of daylight), y₁ … y_{max_depth}.
void trace_light_subpath(Subpaths& p, const LightStarts& starts, Sampler& light_sampler) {
  const auto& lights = *p.scene.lights;
  const int max_depth = p.settings.max_depth;
  const SampledSpectrum initial = p.lanes.initial_ratios();
if (starts.by_power) {
  const float u_choice = light_sampler.next_1d();
  const Vec2 u_position = light_sampler.next_2d(), u_direction = light_sampler.next_2d();
  const auto pick = starts.by_power->sample_discrete(u_choice);
  const float choice = pick.probability;
  const bool from_daylight = size_t(pick.index) == starts.emitting.size();
  PathVertex y0;
  y0.beta = initial;
  y0.ratio = initial;
  SampledSpectrum beta(0.0f), pdf_direction(0.0f);
  std::optional<DaylightRaySampler::DaylightRay> daylight;
  std::optional<DaylightEntry> entry;  // where a ray of daylight meets the first surface that is no pane
  Ray ray;
  ray.time = p.time;
  if (from_daylight) {
    // A ray of daylight from an aperture: y₀ is its direction at infinity, y₁'s density the sampler's p(y, ω).
    daylight = p.scene.daylight_rays->sample(p.lambda, pick.u_remapped, u_direction, u_position);
    // Its panes (between the sky and the aperture as well, an outer pane, or an overhang blocking it) are passed
    // as shadow rays pass them: next-event estimation from the point met passes them so, and the density of
    // this technique (the sampler's p(y, ω)) has no lobe choice in it. A first version traced the ray from the
    // aperture inwards only and skipped what lay outside (the double-glazed room came out 34 % bright).
    if (daylight) entry = enter_through_aperture(p.scene, *daylight, p.lambda, p.time);
    if (entry) {
      y0.kind = VertexKind::light_at_infinity;
      y0.ng = daylight->to_light;
      y0.light = daylight->light;
      y0.pdf_emit = choice;
      y0.hittable = !daylight->is_delta;
      ray.direction = -daylight->to_light;
      beta = initial * daylight->radiance * entry->passage.transmittance;
    }
  } else {
    const int light_index = starts.emitting[size_t(pick.index)];
    const std::optional<EmissionSample> e =
        lights[size_t(light_index)]->sample_emission(pick.u_remapped, u_position, u_direction, p.lambda);
    if (e && choice > 0.0f && e->pdf_direction > 0.0f && e->pdf_position > 0.0f) {
      y0.kind = VertexKind::light;
      y0.position = e->origin_m;
      y0.ng = e->normal;
      y0.light = light_index;
      y0.pdf_emit = choice * e->pdf_position;
      y0.hittable = !(e->normal == Vec3{});
      y0.hit.position = e->origin_m;
      y0.hit.geometric_normal = e->normal;
      y0.hit.primitive = e->primitive;
      y0.hit.light = light_index;
      beta = initial * e->weight / Float4(choice);
      pdf_direction = SampledSpectrum(e->pdf_direction);
      ray.origin = e->normal == Vec3{} ? e->origin_m
                                       : offset_ray_origin(e->origin_m, e->normal, e->direction, p.scene.scene_scale);
      ray.direction = e->direction;
    }
  }
  if (y0.light >= 0) {
    y0.pdf_fwd = SampledSpectrum(y0.pdf_emit);
    p.light.push_back(y0);
    const int light_index = y0.light;
    SampledSpectrum ratio = initial;
    float unit = 1.0f;  // the flux at y₁, Russian roulette's unit
    PaneEdge edge;
    for (int k = 1; max_lane(abs(beta)) > 0.0f;) {
      const std::optional<SurfaceHit> hit =
          k == 1 && entry ? std::optional<SurfaceHit>(entry->hit) : p.scene.geometry->intersect(ray);
      if (!hit) break;
      PathVertex v;
      v.beta = beta;
      v.ratio = ratio;
      v.pass_in = edge.pass;
      if (!p.make_surface_vertex(*hit, -ray.direction, v)) break;
      if (k == 1 && entry) {
        // p(y, ω) per m² at y (and per sr for a sun of finite size), the source's choice included; the throughput
        // L T |n_y·ω| / p(y, ω) (its cosine cancels). The panes on the way were passed deterministically: a camera
        // subpath walking this edge the other way passes them by its lobe choices (y₀'s reverse density).
        const float density = p.scene.daylight_rays->density(light_index, hit->position, hit->geometric_normal,
                                                            daylight->to_light, daylight->direction_pdf);
        if (!(density > 0.0f)) break;
        v.pdf_fwd = SampledSpectrum(density);
        v.pass_in = entry->passage.pass_probability;
        v.beta = beta * Float4(std::fabs(dot(hit->geometric_normal, daylight->to_light)) / (choice * density));
        beta = v.beta;
      } else {
        v.pdf_fwd = p.light.back().delta ? SampledSpectrum(1.0f)
                                         : to_area(pdf_direction, p.light.back().position, v) * edge.pass;
      }
      // A pane is sampled even at the depth limit: the vertex beyond it is the subpath's last one then. (A ray of
      // daylight's first surface is never one: enter_through_aperture passed them.)
      const bool pane = v.pane && edge.open() && !(k == 1 && entry);
      std::optional<BsdfSample> bs;
      float u_roulette = 0.0f;
      if (pane || k < max_depth) {
        const float u_lobe = light_sampler.next_1d();
        const Vec2 u = light_sampler.next_2d();
        bs = v.bsdf->sample(v.wo, u_lobe, u);
        u_roulette = light_sampler.next_1d();
        if (bs && bs->pdf[0] > 0.0f && p.passes(v, *bs, *hit, edge, beta, ratio, ray)) continue;
      }
      p.light.push_back(std::move(v));
      if (k == 1) {
        unit = max_lane(abs(beta)) > 0.0f ? max_lane(abs(beta)) : 1.0f;
        PathVertex& first = p.light[0];
        if (daylight) {
          first.pdf_nee = p.nee_density(p.light[1], light_index, daylight->to_light, nullptr);
        } else {
          first.pdf_nee = p.nee_density(p.light[1], light_index, normalize(first.position - hit->position),
                                        first.ng == Vec3{} ? nullptr : &first.hit);
        }
      }
      if (k >= max_depth) break;
      PathVertex& here = p.light.back();
      if (!bs || !(bs->pdf[0] > 0.0f)) break;
      const Vec3 wi = here.world(bs->wi);
      if (!here.on_side(wi)) break;
      p.record_scattering(p.light, *bs, pdf_direction, ratio);
      edge = {};
      // Flux: the radiance scaling of a refraction undone, and the adjoint's shading-normal factor.
      const float scale = std::fabs(bs->wi.z) / bs->pdf[0] * bs->eta * bs->eta *
                          adjoint_shading_factor(here.world(here.wo), wi, here.frame.n, here.ng);
      beta *= bs->f * Float4(scale);
      p.lanes.keep_followed_lanes(bs->wavelength_dependent_direction, ratio, beta);
      if (!p.survives(beta, ratio, 1.0f, unit, k, u_roulette, beta)) break;
      ray.origin = offset_ray_origin(*hit, wi, p.scene.scene_scale);
      ray.direction = wi;
      ray.t_min = 0.0f;
      ray.t_max = INFINITY;
      ++k;
    }
  }
}

}

// A light subpath kept by the merging pass (StoredLightVertex), back into p.light as trace_light_subpath made it: a
// surface vertex's BSDF and frame rebuilt from its hit (the same material at the same wavelengths gives the same).
void rebuild_light_subpath(Subpaths& p, const StoredLightVertex* stored, int length) {
  for (int i = 0; i < length; ++i) {
    const StoredLightVertex& s = stored[i];
    PathVertex v;
    if (VertexKind(s.kind) == VertexKind::surface) {
      p.make_surface_vertex(s.hit, s.wo_world, v);
    } else {
      v.kind = VertexKind(s.kind);
      v.position = s.position;
      v.ng = s.normal;
      v.hit = s.hit;
    }
    v.beta = s.beta;
    v.ratio = s.ratio;
    v.pdf_fwd = s.pdf_fwd;
    v.pdf_rev = s.pdf_rev;
    v.pass_in = s.pass_in;
    v.delta = s.delta;
    v.light = s.light;
    v.pdf_nee = s.pdf_nee;
    v.pdf_emit = s.pdf_emit;
    v.hittable = s.hittable;
    p.light.push_back(std::move(v));
  }
}

}  // namespace

SampledSpectrum BidirectionalPathIntegrator::radiance(const Ray& camera_ray, const SampledWavelengths& lambda,
                                                      Sampler& camera_sampler, Sampler& light_sampler,
                                                      std::vector<CausticSplat>& splats,
                                                      const LightGroupRadiance& groups,
                                                      const MergeContext* merging) const {
  thread_local std::vector<PathVertex> camera_storage, light_storage;
  thread_local std::vector<JoinedVertex> joined;
  camera_storage.clear();
  light_storage.clear();
  Subpaths p{scene_, settings_, lambda, LaneTechniques{settings_.wavelengths}, camera_ray.time, camera_storage,
             light_storage};
  const auto& lights = *scene_.lights;
  const int max_depth = settings_.max_depth;
  const SampledSpectrum initial = p.lanes.initial_ratios();

  // ---- The camera subpath: z₀ on the lens, z₁ … z_{max_depth+1} (the last only to find an emitter).
  {
    PathVertex z0;
    z0.kind = VertexKind::camera;
    z0.position = camera_ray.origin;
    z0.beta = initial;
    z0.ratio = initial;
    p.camera.push_back(z0);
    SampledSpectrum beta = initial, ratio = initial;
    float eta_scale = 1.0f;
    SampledSpectrum pdf_direction(camera_.direction_density(camera_ray.direction, p.time) / film_pixels_);
    PaneEdge edge;
    Ray ray = camera_ray;
    for (int k = 1;;) {
      const std::optional<SurfaceHit> hit = scene_.geometry->intersect(ray);
      PathVertex v;
      v.beta = beta;
      v.ratio = ratio;
      v.pass_in = edge.pass;
      const PathVertex& previous = p.camera.back();
      if (!hit) {
        if (!scene_.infinite_lights.empty()) {
          v.kind = VertexKind::light_at_infinity;
          v.ng = ray.direction;
          v.pdf_fwd = previous.delta ? SampledSpectrum(1.0f) : pdf_direction * edge.pass;
          p.camera.push_back(std::move(v));
        }
        break;
      }
      const bool scatters = p.make_surface_vertex(*hit, -ray.direction, v);
      // A delta lobe's density counts 1 wherever it appears, unconverted (pdf_rev below does the same).
      v.pdf_fwd = previous.delta ? SampledSpectrum(1.0f) : to_area(pdf_direction, previous.position, v) * edge.pass;
      if (hit->light >= 0) {
        const Light& light = *lights[size_t(hit->light)];
        v.light = hit->light;
        v.emitted = light.radiance(*hit, -ray.direction, lambda);
        const EmissionDensity e = light.emission_density(hit->geometric_normal, -ray.direction);
        v.pdf_emit = emission_choice_[size_t(hit->light)] * e.position;
        v.emit_direction = e.direction;
        if (previous.kind == VertexKind::surface) v.pdf_nee = p.nee_density(previous, hit->light, ray.direction, &*hit);
      }
      // A pane is sampled even beyond the depth limit: next-event estimation from the last vertex passes it, so the
      // camera subpath must be able to as well (as in the path tracer).
      const bool pane = scatters && v.pane && edge.open();
      if (!pane && (!scatters || k > max_depth)) {
        p.camera.push_back(std::move(v));
        break;
      }
      v.u_light_choice = camera_sampler.next_1d();
      v.u_light = camera_sampler.next_2d();
      const float u_lobe = camera_sampler.next_1d();
      const Vec2 u = camera_sampler.next_2d();
      const std::optional<BsdfSample> bs = v.bsdf->sample(v.wo, u_lobe, u);
      const float u_roulette = camera_sampler.next_1d();
      if (!bs || !(bs->pdf[0] > 0.0f)) {
        p.camera.push_back(std::move(v));
        break;
      }
      if (p.passes(v, *bs, *hit, edge, beta, ratio, ray)) {
        // No roulette at a pane (the path tracer draws its number and ignores it too).
        if (!(max_lane(abs(beta)) > 0.0f)) break;
        continue;
      }
      const Vec3 wi = v.world(bs->wi);
      if (k > max_depth || !v.on_side(wi)) {
        p.camera.push_back(std::move(v));
        break;
      }
      p.camera.push_back(std::move(v));
      p.record_scattering(p.camera, *bs, pdf_direction, ratio);
      edge = {};
      beta *= bs->f * Float4(std::fabs(bs->wi.z) / bs->pdf[0]);
      eta_scale *= bs->eta * bs->eta;
      p.lanes.keep_followed_lanes(bs->wavelength_dependent_direction, ratio, beta);
      if (!p.survives(beta, ratio, eta_scale, 1.0f, k, u_roulette, beta)) break;
      if (!(max_lane(abs(beta)) > 0.0f)) break;
      ray.origin = offset_ray_origin(*hit, wi, scene_.scene_scale);
      ray.direction = wi;
      ray.t_min = 0.0f;
      ray.t_max = INFINITY;
      ++k;
    }
  }

  if (merging && merging->reuse_light_subpath)
    rebuild_light_subpath(p, merging->light_subpath, merging->light_subpath_length);
  else
    trace_light_subpath(p, LightStarts{by_power_ ? &*by_power_ : nullptr, emitting_}, light_sampler);

  // ---- Joining them.
  SampledSpectrum radiance(0.0f);
  // Each contribution, credited to its light's group as well (light_group_radiance.h).
  auto contribute = [&](int light_index, const SampledSpectrum& contribution) {
    radiance += contribution;
    if (groups.groups) groups.add(lights[size_t(light_index)]->light_group(), contribution);
  };
  // The daylight rays' density p(y, ω) of a vertex y lit from `to_light` by light `index` (its sample_li density
  // `direction_pdf`, used for a sun); 0 for lights that are no daylight source, and without daylight subpaths.
  auto daylight_density = [&](int index, const PathVertex& y, Vec3 to_light, float direction_pdf) {
    if (!(daylight_choice_ > 0.0f)) return 0.0f;
    return scene_.daylight_rays->density(index, y.position, y.hit.geometric_normal, to_light, direction_pdf);
  };
  const int camera_count = int(p.camera.size()), light_count = int(p.light.size());
  joined.resize(size_t(camera_count + light_count + 2));

  // f·|cos| at a camera vertex towards w (world), and its adjoint at a light vertex (with the shading factor).
  auto f_camera = [&](const PathVertex& z, Vec3 w) {
    if (!z.on_side(w)) return SampledSpectrum(0.0f);
    const Vec3 local = z.frame.to_local(w);
    return z.bsdf->eval(z.wo, local) * Float4(std::fabs(local.z));
  };
  auto f_light = [&](const PathVertex& y, Vec3 w) {
    if (!y.on_side(w)) return SampledSpectrum(0.0f);
    const Vec3 local = y.frame.to_local(w);
    const float factor = std::fabs(local.z) * adjoint_shading_factor(y.world(y.wo), w, y.frame.n, y.ng);
    return y.bsdf->eval(local, y.wo) * Float4(factor);
  };
  // The density y's BSDF gives w_out when its light arrived along w_in (both world, pointing away from y).
  auto bsdf_pdf = [&](const PathVertex& v, Vec3 w_in, Vec3 w_out) {
    return p.lanes.densities(v.bsdf->pdf(v.frame.to_local(w_in), v.frame.to_local(w_out)));
  };
  // The joined path's densities: light vertices y₀ … y_{s−1}, then camera vertices z_{t−1} … z₀.
  auto fill = [&](int s, int t) {
    const int n = s + t;
    for (int i = 0; i < s; ++i) {
      const PathVertex& y = p.light[size_t(i)];
      joined[size_t(i)] = {y.pdf_fwd, y.pdf_rev, i >= 1 && y.connectible()};
    }
    for (int j = 0; j < t; ++j) {
      const PathVertex& z = p.camera[size_t(j)];
      joined[size_t(n - 1 - j)] = {z.pdf_rev, z.pdf_fwd, j >= 1 && z.connectible()};
    }
    return n;
  };
  // Vertex merging's c = π r² N for this sample's bucket (0: no merging): every technique's weight counts the merges.
  const float merge_factor = merging ? merging->pass->merge_factor(merging->bucket) : 0.0f;
  auto finish = [&](int n, int s, const SampledSpectrum& ratio, const SampledSpectrum& value, float p_nee,
                    float p_emit, bool hittable, bool merge = false) {
    const SampledSpectrum sums = technique_sum(joined.data(), n, s, p_nee, p_emit, hittable, merge_factor, merge);
    const float denominator = sum(ratio * sums);
    if (!(denominator > 0.0f) || !std::isfinite(denominator)) return SampledSpectrum(0.0f);
    return value * Float4(kLanes / denominator);
  };

  for (int t = 2; t <= camera_count; ++t) {
    const PathVertex& z = p.camera[size_t(t - 1)];
    const PathVertex& z_previous = p.camera[size_t(t - 2)];
    // s = 0: z is on an emitter (or at infinity).
    if (z.kind == VertexKind::light_at_infinity) {
      for (int index : scene_.infinite_lights) {
        const Light& light = *lights[size_t(index)];
        const SampledSpectrum le = light.radiance_escaped(z.ng, lambda);
        if (!(max_lane(le) > 0.0f)) continue;
        const int n = fill(0, t);
        joined[0].connectible = false;
        float p_nee = 0.0f;
        joined[1].pf = SampledSpectrum(0.0f);
        if (z_previous.kind == VertexKind::surface) {
          const int part = scene_.light_sampler->part_of_hit(0);
          const float pdf_li = light.pdf_part_li(part, LightReference{z_previous.position, z_previous.ng}, z.ng);
          p_nee = scene_.light_sampler->pmf(p.sampling_point(z_previous), index, part) * pdf_li;
          joined[1].pf = SampledSpectrum(daylight_density(index, z_previous, z.ng, pdf_li));
        }
        contribute(index, finish(n, 0, z.ratio, z.beta * le, p_nee, daylight_choice_, !light.is_delta()));
      }
      continue;
    }
    if (z.light >= 0 && max_lane(z.emitted) > 0.0f) {
      const int n = fill(0, t);
      joined[0].connectible = false;
      if (n >= 2) joined[1].pf = to_area(SampledSpectrum(z.emit_direction), z.position, z_previous) * z.pass_in;
      contribute(z.light, finish(n, 0, z.ratio, z.beta * z.emitted, z.pdf_nee, z.pdf_emit, true));
    }
    // The joined end needs a non-delta component; how its own subpath went on from it does not matter.
    if (!z.bsdf || !z.non_delta) continue;

    // s = 1: next-event estimation from z (not beyond the depth limit: z is the (t−1)th scattering vertex).
    if (t - 1 <= max_depth && !lights.empty()) {
      const LightSampler& sampler = *scene_.light_sampler;
      if (const auto pick = sampler.sample(p.sampling_point(z), z.u_light_choice)) {
        const Light& light = *lights[size_t(pick->light)];
        const std::optional<LightSample> ls =
            light.sample_part_li(pick->part, LightReference{z.position, z.ng}, lambda, z.u_light);
        if (ls && ls->pdf_solid_angle > 0.0f && max_lane(ls->radiance) > 0.0f) {
          const SampledSpectrum f = f_camera(z, ls->wi);
          if (max_lane(f) > 0.0f) {
            Ray shadow;
            shadow.time = p.time;
            shadow.origin = offset_ray_origin(z.hit, ls->wi, scene_.scene_scale);
            const ShadowSegment segment = shadow_segment(shadow.origin, z.position, *ls, scene_.scene_scale);
            shadow.direction = segment.direction;
            shadow.t_max = std::isinf(segment.length) ? segment.length : segment.length * (1.0f - 0x1p-12f);
            if (const std::optional<ShadowPassage> passage = trace_shadow(scene_, shadow, lambda)) {
              // Both walks would pass the panes on this edge by their lobe choices (PathVertex::pass_in).
              const SampledSpectrum& pass = passage->pass_probability;
              PathVertex x0;
              const bool at_infinity = !std::isfinite(ls->distance);
              x0.kind = at_infinity ? VertexKind::light_at_infinity : VertexKind::light;
              x0.position = at_infinity ? Vec3{} : z.position + ls->wi * ls->distance;
              x0.ng = ls->normal;
              const float choice_density = pick->probability * ls->pdf_solid_angle;
              float p_nee = choice_density;
              if (!ls->is_delta && !at_infinity)
                p_nee *= std::fabs(dot(ls->normal, ls->wi)) / (ls->distance * ls->distance);
              const EmissionDensity e = light.emission_density(ls->normal, -ls->wi);
              const float p_emit = at_infinity ? daylight_choice_ : emission_choice_[size_t(pick->light)] * e.position;
              const int n = fill(0, t) + 1;
              // Shift the camera vertices up by one: x₀ is the light.
              for (int i = n - 1; i >= 1; --i) joined[size_t(i)] = joined[size_t(i - 1)];
              joined[0] = {SampledSpectrum(0.0f), SampledSpectrum(0.0f), false};
              joined[0].pc = (at_infinity || ls->is_delta
                                  ? bsdf_pdf(z, z.world(z.wo), ls->wi)
                                  : to_area(bsdf_pdf(z, z.world(z.wo), ls->wi), z.position, x0)) *
                             pass;
              joined[1].connectible = true;
              // Daylight subpaths pass their panes deterministically (enter_through_aperture).
              joined[1].pf = at_infinity ? SampledSpectrum(daylight_density(pick->light, z, ls->wi, ls->pdf_solid_angle))
                                         : to_area(SampledSpectrum(e.direction), x0.position, z) * pass;
              if (t >= 3) joined[2].pf = to_area(bsdf_pdf(z, ls->wi, z.world(z.wo)), z.position, z_previous) * z.pass_in;
              const SampledSpectrum value =
                  z.beta * f * ls->radiance * passage->transmittance / Float4(choice_density);
              contribute(pick->light, finish(n, 1, z.ratio, value, p_nee, p_emit, !ls->is_delta));
            }
          }
        }
      }
    }

    // s ≥ 2: y_{s−1} joined to z.
    for (int s = 2; s <= light_count && s + t - 2 <= max_depth; ++s) {
      const PathVertex& y = p.light[size_t(s - 1)];
      if (!y.non_delta) continue;
      const Vec3 to_z = z.position - y.position;
      const float d2 = length_squared(to_z);
      if (!(d2 > 0.0f) || !std::isfinite(d2)) continue;
      const Vec3 w_yz = to_z / std::sqrt(d2);
      const SampledSpectrum fy = f_light(y, w_yz), fz = f_camera(z, -w_yz);
      const SampledSpectrum value = y.beta * fy * fz * z.beta / Float4(d2);
      if (!(max_lane(abs(value)) > 0.0f)) continue;
      Ray shadow;
      shadow.time = p.time;
      shadow.origin = offset_ray_origin(z.hit, -w_yz, scene_.scene_scale);
      const Vec3 target = offset_ray_origin(y.hit, w_yz, scene_.scene_scale);
      const ShadowSegment segment = shadow_segment(shadow.origin, target, -w_yz);
      shadow.direction = segment.direction;
      shadow.t_max = segment.length * (1.0f - 0x1p-12f);
      if (segment.length <= 0.0f) continue;
      const std::optional<ShadowPassage> passage = trace_shadow(scene_, shadow, lambda);
      if (!passage) continue;
      const SampledSpectrum& pass = passage->pass_probability;
      const int n = fill(s, t);
      const PathVertex& y_previous = p.light[size_t(s - 2)];
      joined[size_t(s - 1)].connectible = joined[size_t(s)].connectible = true;
      joined[size_t(s)].pf = to_area(bsdf_pdf(y, y.world(y.wo), w_yz), y.position, z) * pass;
      if (t >= 3)
        joined[size_t(s + 1)].pf = to_area(bsdf_pdf(z, -w_yz, z.world(z.wo)), z.position, z_previous) * z.pass_in;
      joined[size_t(s - 1)].pc = to_area(bsdf_pdf(z, z.world(z.wo), -w_yz), z.position, y) * pass;
      joined[size_t(s - 2)].pc = to_area(bsdf_pdf(y, w_yz, y.world(y.wo)), y.position, y_previous) * y.pass_in;
      const PathVertex& y0 = p.light[0];
      contribute(y0.light, finish(n, s, y.ratio * z.ratio, value * passage->transmittance, y0.pdf_nee, y0.pdf_emit,
                                  y0.hittable));
    }

    // Merges: z with the pass's light vertices of its bucket within the radius (vertex_merging.h). Light vertex y_i
    // stands for z: the path is y₀ … y_{i−1}, z, z_{t−2} … z₀, and z's BSDF scatters the light y_i received.
    if (merging && t - 1 <= max_depth) {
      const VertexMergingPass& pass = *merging->pass;
      pass.for_each_within(z.position, merging->bucket, [&](const MergeVertex& m, const MergeSubpath& subpath,
                                                             const JoinedVertex* light_densities) {
        const int i = m.index, n = i + t;
        if (n - 2 > max_depth || !z.on_side(m.w_light)) return;
        // The photons' density is per area of the surface (their irradiance is the geometric normal's), the BSDF's
        // cosine the shading normal's, as a connection's.
        const float cos_geometric = std::fabs(dot(z.ng, m.w_light));
        if (!(cos_geometric > 0.0f)) return;
        const Vec3 local = z.frame.to_local(m.w_light);
        const SampledSpectrum value = z.beta * z.bsdf->eval(z.wo, local) * m.beta *
                                      Float4(std::fabs(local.z) / (cos_geometric * merge_factor));
        if (!(max_lane(abs(value)) > 0.0f)) return;
        if (joined.size() < size_t(n + 1)) joined.resize(size_t(n + 1));
        for (int k = 0; k < i; ++k) joined[size_t(k)] = light_densities[k];
        for (int j = 0; j < t; ++j) {
          const PathVertex& zj = p.camera[size_t(j)];
          joined[size_t(n - 1 - j)] = {zj.pdf_rev, zj.pdf_fwd, j >= 1 && zj.connectible()};
        }
        joined[size_t(i)].pf = m.pdf_fwd;
        joined[size_t(i)].connectible = true;
        joined[size_t(i - 1)].pc = to_area(bsdf_pdf(z, z.world(z.wo), m.w_light), z.position, m.previous_position,
                                           m.previous_normal, m.previous_at_infinity) *
                                   m.pass_in;
        if (t >= 3)
          joined[size_t(i + 1)].pf = to_area(bsdf_pdf(z, m.w_light, z.world(z.wo)), z.position, z_previous) * z.pass_in;
        contribute(subpath.light, finish(n, i, m.ratio * z.ratio, value, subpath.pdf_nee, subpath.pdf_emit,
                                         subpath.hittable, true));
      });
    }
  }

  // t = 1: y_{s−1} seen by the camera, splatted.
  for (int s = 2; s <= light_count && s - 1 <= max_depth; ++s) {
    const PathVertex& y = p.light[size_t(s - 1)];
    if (!y.non_delta) continue;
    const Vec2 u_lens = light_sampler.next_2d();
    const auto seen = camera_.see(y.position, p.time, u_lens);
    if (!seen) continue;
    const Vec3 to_camera = seen->camera_position_m - y.position;
    const float distance = length(to_camera);
    if (!(distance > 0.0f)) continue;
    const Vec3 w = to_camera / distance;
    const SampledSpectrum value = y.beta * f_light(y, w) * Float4(seen->importance);
    if (!(max_lane(abs(value)) > 0.0f)) continue;
    Ray shadow;
    shadow.time = p.time;
    shadow.origin = offset_ray_origin(y.hit, w, scene_.scene_scale);
    shadow.direction = w;
    shadow.t_max = length(seen->camera_position_m - shadow.origin) * (1.0f - 0x1p-12f);
    const std::optional<ShadowPassage> passage = trace_shadow(scene_, shadow, lambda);
    if (!passage) continue;
    const int n = fill(s, 1);  // the lens vertex's own densities are never read (no technique reaches the lens)
    joined[size_t(s - 1)].connectible = true;
    joined[size_t(s - 1)].pc =
        to_area(SampledSpectrum(camera_.direction_density(-w, p.time) / film_pixels_), seen->camera_position_m, y) *
        passage->pass_probability;
    joined[size_t(s - 2)].pc = to_area(bsdf_pdf(y, w, y.world(y.wo)), y.position, p.light[size_t(s - 2)]) * y.pass_in;
    const PathVertex& y0 = p.light[0];
    SampledSpectrum contribution =
        finish(n, s, y.ratio, value * passage->transmittance, y0.pdf_nee, y0.pdf_emit, y0.hittable);
    if (settings_.wavelengths == WavelengthMode::single) contribution *= Float4(1.0f, 0.0f, 0.0f, 0.0f);
    if (max_lane(abs(contribution)) > 0.0f)
      splats.push_back({seen->film_px, contribution, lambda, lights[size_t(y0.light)]->light_group()});
  }

  if (settings_.wavelengths == WavelengthMode::single) {
    const Float4 hero_only(1.0f, 0.0f, 0.0f, 0.0f);
    if (groups.groups) groups.mask(hero_only);
    radiance *= hero_only;
  }
  return radiance;
}

void BidirectionalPathIntegrator::trace_merge_subpath(const SampledWavelengths& lambda, int bucket, float time,
                                                      Sampler& sampler, MergeVertexBatch& batch) const {
  thread_local std::vector<PathVertex> unused_camera, light_storage;
  light_storage.clear();
  Subpaths p{scene_, settings_, lambda, LaneTechniques{settings_.wavelengths}, time, unused_camera, light_storage};
  trace_light_subpath(p, LightStarts{by_power_ ? &*by_power_ : nullptr, emitting_}, sampler);
  batch.stored_start.push_back(uint32_t(batch.stored.size()));
  for (const PathVertex& y : p.light) {
    StoredLightVertex s;
    s.hit = y.hit;
    s.position = y.position;
    s.normal = y.ng;
    if (y.kind == VertexKind::surface) s.wo_world = y.world(y.wo);
    s.beta = y.beta;
    s.ratio = y.ratio;
    s.pdf_fwd = y.pdf_fwd;
    s.pdf_rev = y.pdf_rev;
    s.pass_in = y.pass_in;
    s.pdf_nee = y.pdf_nee;
    s.pdf_emit = y.pdf_emit;
    s.light = y.light;
    s.kind = uint8_t(y.kind);
    s.delta = y.delta;
    s.hittable = y.hittable;
    batch.stored.push_back(s);
  }
  const auto subpath = uint32_t(batch.subpaths.size());
  bool any = false;
  for (size_t i = 1; i < p.light.size(); ++i) {
    const PathVertex& y = p.light[i];
    if (!y.non_delta || y.kind != VertexKind::surface) continue;
    const PathVertex& previous = p.light[i - 1];
    MergeVertex m;
    m.position = y.position;
    m.w_light = y.world(y.wo);
    m.previous_position = previous.position;
    m.previous_normal = previous.ng;
    m.previous_at_infinity = previous.kind == VertexKind::light_at_infinity;
    m.beta = y.beta;
    m.ratio = y.ratio;
    m.pdf_fwd = y.pdf_fwd;
    m.pass_in = y.pass_in;
    m.subpath = subpath;
    m.index = uint16_t(i);
    m.bucket = uint16_t(bucket);
    batch.vertices.push_back(m);
    any = true;
  }
  if (!any) return;
  MergeSubpath s;
  s.first_density = uint32_t(batch.densities.size());
  s.light = p.light[0].light;
  s.pdf_nee = p.light[0].pdf_nee;
  s.pdf_emit = p.light[0].pdf_emit;
  s.hittable = p.light[0].hittable;
  batch.subpaths.push_back(s);
  for (size_t i = 0; i < p.light.size(); ++i) {
    const PathVertex& y = p.light[i];
    batch.densities.push_back({y.pdf_fwd, y.pdf_rev, i >= 1 && y.connectible()});
  }
}

}  // namespace rimu
