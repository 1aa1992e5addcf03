#include "transport/integrators/shadow_passage.h"

#include <cmath>
#include <variant>

#include "transport/integrators/path_integrator.h"

namespace rimu {

std::optional<ThinDielectricBsdf::StraightThrough> straight_through_at(const Material& material, const SurfaceHit& hit,
                                                                       Vec3 direction, const SampledWavelengths& lambda) {
  if (!material.passes_shadow_rays()) return std::nullopt;
  // The same BSDF the path would build here (its shading normal included), so that the transmittance and the lobe
  // probability are exactly those BSDF sampling uses for this direction.
  MaterialContext context = MaterialContext::at(hit, -direction);
  context.shading_normal = material.shading_normal(context);
  const Bsdf bsdf = material.bsdf(context, lambda);
  const auto* sheet = std::get_if<ThinDielectricBsdf>(&bsdf.variant());
  if (!sheet) return std::nullopt;
  return sheet->straight_through(std::fabs(dot(direction, context.shading_normal)));
}

bool ShadowPassage::pass_surface(const Material& material, const SurfaceHit& hit, Vec3 light_direction,
                                 const SampledWavelengths& lambda) {
  if (surfaces == kMaxShadowPassages) return false;
  const auto through = straight_through_at(material, hit, light_direction, lambda);
  if (!through) return false;
  pass(*through);
  return max_lane(transmittance) > 0.0f;
}

PaneWalk pass_panes(const TransportScene& scene, const Ray& ray, Vec3 light_direction, const SampledWavelengths& lambda,
                    ShadowPassage& passage) {
  Ray segment = ray;
  for (;;) {
    std::optional<SurfaceHit> hit = scene.geometry->intersect(segment);
    if (!hit) return {};
    if (hit->material < 0 || !(scene.passable_surfaces && (*scene.materials)[size_t(hit->material)].passes_shadow_rays()))
      return {PaneWalk::End::surface, std::move(hit)};
    if (!passage.pass_surface((*scene.materials)[size_t(hit->material)], *hit, light_direction, lambda))
      return {PaneWalk::End::blocked, std::nullopt};
    // Continue from the far side of the pane, up to the same end point.
    segment.origin = offset_ray_origin(*hit, ray.direction, scene.scene_scale);
    segment.t_min = 0.0f;
    if (!std::isinf(ray.t_max)) {
      const Vec3 end = ray.origin + ray.direction * ray.t_max;
      segment.t_max = dot(end - segment.origin, ray.direction);
      if (!(segment.t_max > 0.0f)) return {};
    }
  }
}

std::optional<ShadowPassage> trace_shadow(const TransportScene& scene, const Ray& ray, const SampledWavelengths& lambda) {
  if (!scene.passable_surfaces) {
    if (scene.geometry->occluded(ray)) return std::nullopt;
    return ShadowPassage{};
  }
  ShadowPassage out;
  if (pass_panes(scene, ray, ray.direction, lambda, out).end != PaneWalk::End::reached_end) return std::nullopt;
  return out;
}

}  // namespace rimu
