// Shadow rays through glazing: surfaces whose transmission does not bend rays (thin dielectrics) let next-event
// estimation through, weighted by their transmittance (docs/transport.md, "Glazing: shadow rays through panes").
#pragma once

#include <optional>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/bsdfs/material.h"
#include "transport/geometry/ray.h"
#include "transport/geometry/surface_hit.h"
#include "transport/bsdfs/thin_dielectric_bsdf.h"

namespace rimu {

struct TransportScene;

/// At most this many pass-through surfaces on one shadow ray, and on one path segment between two scattering
/// vertices: a shadow ray meeting a ninth is blocked, and a path passing a ninth makes it an ordinary specular
/// vertex, so that next-event estimation and BSDF sampling cover exactly the same paths (the MIS stays exact).
inline constexpr int kMaxShadowPassages = 8;

/// The straight-through lobe of `material` at `hit` for a ray travelling along `direction` (per lane: what passes,
/// and the probability BSDF sampling picks that lobe, as the material's own BSDF defines them at that angle), or
/// nothing if shadow rays cannot pass it (Material::passes_shadow_rays).
std::optional<ThinDielectricBsdf::StraightThrough> straight_through_at(const Material& material, const SurfaceHit& hit,
                                                                       Vec3 direction, const SampledWavelengths& lambda);

/// What a shadow ray brings back when nothing opaque blocks it: the product of the transmittances of the surfaces it
/// passed, and the product of the probabilities that BSDF sampling would have passed them (for the MIS weight).
struct ShadowPassage {
  SampledSpectrum transmittance{1.0f};
  SampledSpectrum pass_probability{1.0f};
  int surfaces = 0;  ///< how many it passed (at most kMaxShadowPassages)

  /// The passage through `through` as well (one more surface).
  void pass(const ThinDielectricBsdf::StraightThrough& through) {
    transmittance *= through.transmittance;
    pass_probability *= through.probability;
    ++surfaces;
  }
  /// The passage through the surface of `material` at `hit` as well, for light travelling along `light_direction`;
  /// false where the shadow ray is blocked there: kMaxShadowPassages passed already, a material shadow rays cannot
  /// pass (straight_through_at), or no light left. Every walk through panes (pass_panes, the volumetric
  /// integrator's shadow rays) passes a surface by this one rule.
  bool pass_surface(const Material& material, const SurfaceHit& hit, Vec3 light_direction,
                    const SampledWavelengths& lambda);
};

/// Where a ray walked through pass-through surfaces (pass_panes) ended.
struct PaneWalk {
  enum class End {
    reached_end,  ///< nothing but panes up to the ray's t_max
    surface,      ///< at `surface`, the first surface not passed (opaque, refracting, or an emitter without material)
    blocked       ///< at a pane it could not pass: a ninth (kMaxShadowPassages), or one that left no light
  };
  End end = End::reached_end;
  std::optional<SurfaceHit> surface;
};

/// Closest hits along `ray` (up to its t_max) through the surfaces shadow rays pass (when
/// TransportScene::passable_surfaces), multiplying into `passage` what each passes of light travelling along
/// `light_direction`: ray.direction for a shadow ray, its reverse for a ray traced in from the light's side (the
/// daylight rays of daylit_connection.h). At most kMaxShadowPassages surfaces in `passage` in all.
PaneWalk pass_panes(const TransportScene& scene, const Ray& ray, Vec3 light_direction, const SampledWavelengths& lambda,
                    ShadowPassage& passage);

/// A shadow ray in a scene without media: one occlusion query when the scene has no pass-through surface
/// (TransportScene::passable_surfaces false), else closest hits until the light, multiplying the transmittance of
/// each pass-through surface met. std::nullopt when blocked (an opaque or refracting surface, or more than
/// kMaxShadowPassages panes).
std::optional<ShadowPassage> trace_shadow(const TransportScene& scene, const Ray& ray, const SampledWavelengths& lambda);

}  // namespace rimu
