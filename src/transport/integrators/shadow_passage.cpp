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

std::optional<ShadowPassage> trace_shadow(const TransportScene& scene, const Ray& ray, const SampledWavelengths& lambda) {
  if (!scene.passable_surfaces) {
    if (scene.geometry->occluded(ray)) return std::nullopt;
    return ShadowPassage{};
  }
  ShadowPassage out;
  Ray segment = ray;
  for (int passed = 0;; ++passed) {
    const std::optional<SurfaceHit> hit = scene.geometry->intersect(segment);
    if (!hit) return out;
    if (passed == kMaxShadowPassages || hit->material < 0) return std::nullopt;
    const auto through = straight_through_at((*scene.materials)[size_t(hit->material)], *hit, ray.direction, lambda);
    if (!through) return std::nullopt;
    out.pass(*through);
    if (!(max_lane(out.transmittance) > 0.0f)) return std::nullopt;
    // Continue from the far side of the pane, up to the same end point.
    const Vec3 end = ray.origin + ray.direction * ray.t_max;
    segment.origin = offset_ray_origin(*hit, ray.direction, scene.scene_scale);
    segment.t_min = 0.0f;
    segment.t_max = std::isinf(ray.t_max) ? ray.t_max : dot(end - segment.origin, ray.direction);
    if (!(segment.t_max > 0.0f)) return out;
  }
}

}  // namespace rimu
