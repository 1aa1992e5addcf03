// Triangle meshes as the scene holds them (world space after transforms, or a prototype's object space).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "transport/transform.h"
#include "transport/vector.h"

namespace rimu {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;   ///< per vertex, optional (empty = flat shading)
  std::vector<Vec2> uvs;       ///< per vertex, optional
  std::vector<uint32_t> indices;  ///< three per triangle, counter-clockwise seen from the front

  size_t triangle_count() const { return indices.size() / 3; }
  /// Applies `t` to positions and normals; flips the winding if `t` mirrors (determinant < 0).
  void transform(const Transform& t);
  /// Removes triangles whose area is zero or not finite (they would give NaN normals) and returns how many.
  size_t remove_degenerate_triangles();
  /// Checks indices are in range and every number is finite; returns an empty string or what is wrong.
  std::string validate() const;
};

}  // namespace rimu
