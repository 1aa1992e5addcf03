// The largest coordinate a scene may place geometry or the camera at.
//
// Embree 3 (common/math/constants.h) calls a value valid only inside ±FLT_LARGE = 1.844e18: a triangle or sphere
// with a vertex or bound outside is silently left out of the scene, and a ray whose origin lies outside fails the
// assertion at the entry of rtcIntersect1/rtcOccluded1 (Debian's build keeps it: a camera at 2e18 m aborted Rimu).
// Rimu refuses anything beyond 1e18 m at load time instead, naming the key: comfortably inside Embree's bound, so
// the small offsets that lift a ray's origin off a surface cannot cross it (one float step at 1e18 is 6.9e10 m).
#pragma once

#include <array>
#include <string>

#include "render/scene/json_cursor.h"
#include "render/scene/triangle_mesh.h"
#include "transport/geometry/transform.h"
#include "transport/geometry/vector.h"

namespace rimu {

inline constexpr double kMaxCoordinate_m = 1e18;

/// Throws an InputError at `where` if a coordinate of `p` (world space, m) is not finite or exceeds
/// kMaxCoordinate_m in magnitude; `what` names the point in the message ("the camera position").
void check_coordinates(Vec3 p, const JsonCursor& where, const std::string& what);

/// check_coordinates for every vertex of a world-space mesh; the message names the first vertex out of range.
void check_mesh_coordinates(const TriangleMesh& mesh, const JsonCursor& where);

/// Axis-aligned bounds of a set of points, in double precision.
struct BoundsD {
  double min[3] = {0, 0, 0}, max[3] = {0, 0, 0};
  bool empty = true;
  void extend(Vec3 p);
};

/// check_coordinates for the corners of `object_bounds` placed by `object_to_world` (evaluated in double): the
/// transformed box contains every transformed point, so an instance that passes lies inside the limit.
void check_instance_coordinates(const BoundsD& object_bounds, const Transform& object_to_world,
                                const JsonCursor& where);

/// Embree traces an instance's rays in its prototype's space, and checks them there too: a transform that shrinks
/// the prototype a lot maps far ray origins beyond the limit (a 1e-9 scale and a camera 1e10 m away aborted).
/// Checks that the inverse of `object_to_world` maps `world` (a box around every ray origin: the camera and all
/// geometry) within the limit.
void check_instance_ray_space(const BoundsD& world, const Transform& object_to_world, const JsonCursor& where);

}  // namespace rimu
