// What the integrator asks of the geometry: the closest hit, and visibility.
#pragma once

#include <optional>

#include "transport/geometry/ray.h"
#include "transport/geometry/surface_hit.h"

namespace rimu {

/// The geometry as light transport sees it. The renderer implements it with Embree (render/scene/embree_scene.h);
/// tests can implement it analytically. Both calls are thread-safe and allocate nothing.
class RayQueries {
 public:
  virtual ~RayQueries() = default;
  /// Closest hit along the ray within [t_min, t_max].
  virtual std::optional<SurfaceHit> intersect(const Ray& ray) const = 0;
  /// True if anything blocks the ray within [t_min, t_max].
  virtual bool occluded(const Ray& ray) const = 0;
};

}  // namespace rimu
