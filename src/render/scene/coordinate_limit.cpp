#include "render/scene/coordinate_limit.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rimu {
namespace {

bool in_range(double x) { return std::fabs(x) <= kMaxCoordinate_m; }  // false for NaN and ±inf

[[noreturn]] void fail_at(const JsonCursor& where, const std::string& what, const double p[3]) {
  std::ostringstream msg;
  msg.precision(4);
  msg << what << " is (" << p[0] << ", " << p[1] << ", " << p[2] << ") m; coordinates must lie within ±"
      << kMaxCoordinate_m << " m (Embree, which traces the rays, accepts no more than ±1.844e18)";
  where.fail(msg.str());
}

// Fails at the first corner of `box` that the 3×4 row-major `rows` maps out of range: the image of a box lies in
// the hull of its corners' images, so a box that passes is inside the limit everywhere. Evaluated in double.
void check_box_image(const BoundsD& box, const std::array<float, 12>& rows, const JsonCursor& where,
                     const std::string& what) {
  if (box.empty) return;
  for (int corner = 0; corner < 8; ++corner) {
    const double p[3] = {(corner & 1) ? box.max[0] : box.min[0], (corner & 2) ? box.max[1] : box.min[1],
                         (corner & 4) ? box.max[2] : box.min[2]};
    double q[3];
    for (size_t r = 0; r < 3; ++r)
      q[r] = double(rows[4 * r]) * p[0] + double(rows[4 * r + 1]) * p[1] + double(rows[4 * r + 2]) * p[2] +
             double(rows[4 * r + 3]);
    if (!in_range(q[0]) || !in_range(q[1]) || !in_range(q[2])) fail_at(where, what, q);
  }
}

}  // namespace

void check_coordinates(Vec3 p, const JsonCursor& where, const std::string& what) {
  const double d[3] = {p.x, p.y, p.z};
  if (!in_range(d[0]) || !in_range(d[1]) || !in_range(d[2])) fail_at(where, what, d);
}

void check_mesh_coordinates(const TriangleMesh& mesh, const JsonCursor& where) {
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3 p = mesh.positions[i];
    if (!in_range(p.x) || !in_range(p.y) || !in_range(p.z))
      check_coordinates(p, where, "vertex " + std::to_string(i) + " (after the transform)");
  }
}

void BoundsD::extend(Vec3 p) {
  const double d[3] = {p.x, p.y, p.z};
  for (int a = 0; a < 3; ++a) {
    min[a] = empty ? d[a] : std::min(min[a], d[a]);
    max[a] = empty ? d[a] : std::max(max[a], d[a]);
  }
  empty = false;
}

void check_instance_coordinates(const BoundsD& object_bounds, const Transform& object_to_world,
                                const JsonCursor& where) {
  check_box_image(object_bounds, object_to_world.rows(), where,
                  "a corner of the prototype's bounding box, placed by this transform,");
}

void check_instance_ray_space(const BoundsD& world, const Transform& object_to_world, const JsonCursor& where) {
  check_box_image(world, object_to_world.inverse().rows(), where,
                  "a corner of the scene's bounding box (camera and geometry), seen from the prototype's space "
                  "where this instance's rays are traced,");
}

}  // namespace rimu
