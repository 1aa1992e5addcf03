// Triangle meshes as the scene holds them (world space after transforms, or a prototype's object space).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "transport/geometry/transform.h"
#include "transport/geometry/vector.h"

namespace rimu {

struct TriangleMesh {
  std::vector<Vec3> positions;
  /// Per vertex, optional (empty = flat shading). (0, 0, 0) = no normal at this vertex (a PLY file's zero or NaN
  /// normal): a triangle with such a corner is shaded flat, as pbrt-v4 shades one whose interpolated normal is NaN.
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;       ///< per vertex, optional
  std::vector<uint32_t> indices;  ///< three per triangle, counter-clockwise seen from the front
  /// The texture coordinates of a mesh without uvs, the same for every triangle, at its vertices 0, 1, 2.
  enum class DefaultUvs : uint8_t {
    barycentric,   ///< (0,0), (1,0), (0,1): uv = the barycentrics (b1, b2)
    pbrt,          ///< pbrt-v4's (0,0), (1,0), (1,1) (its Triangle without uv): uv = (b1 + b2, b2)
    pbrt_swapped,  ///< pbrt's after vertices 1 and 2 were swapped (a mirroring transform): (0,0), (1,1), (1,0)
  };
  DefaultUvs default_uvs = DefaultUvs::barycentric;

  size_t triangle_count() const { return indices.size() / 3; }
  /// The texture coordinates at barycentrics (b1, b2) of triangle `triangle` (b0 = 1 − b1 − b2, Embree's u and v):
  /// the uvs interpolated; without uvs, the default ones: (b1, b2) itself, pbrt-v4's (b1 + b2, b2), or swapped
  /// (b1 + b2, b1). What a hit sees and what an area light with an emission image reads (scene_shapes.cpp).
  Vec2 uv_at(size_t triangle, float b1, float b2) const {
    if (uvs.empty()) {
      switch (default_uvs) {
        case DefaultUvs::pbrt: return {b1 + b2, b2};
        case DefaultUvs::pbrt_swapped: return {b1 + b2, b1};
        case DefaultUvs::barycentric: break;
      }
      return {b1, b2};
    }
    const uint32_t* tri = &indices[3 * triangle];
    const float b0 = 1.0f - b1 - b2;
    const Vec2 a = uvs[tri[0]], b = uvs[tri[1]], c = uvs[tri[2]];
    return {b0 * a.x + b1 * b.x + b2 * c.x, b0 * a.y + b1 * b.y + b2 * c.y};
  }
  /// Rewinds the triangles whose front by pbrt-v4's rule is not their counter-clockwise side, Rimu's front (the pbrt
  /// importer's meshes: docs/scene-format.md, mesh "front"). pbrt's front is the side the shading normals point to
  /// where all three corners have one (a (0, 0, 0) normal orients nothing), else the counter-clockwise side;
  /// `reversed` (pbrt's ReverseOrientation, or a shape turned inside out to bound the medium in front of it) flips
  /// both, and negates the normals. Rewinding swaps corners 1 and 2, so a mesh without uvs whose default is pbrt's
  /// per-triangle (0,0), (1,0), (1,1) first gets its corners as vertices of their own with those uvs (in the
  /// order read) if any triangle is rewound. Returns the number of triangles rewound.
  size_t turn_to_pbrt_front(bool reversed);
  /// Applies `t` to positions and normals; flips the winding if `t` mirrors (determinant < 0).
  void transform(const Transform& t);
  /// Removes triangles whose area is zero or not finite (they would give NaN normals) and returns how many.
  size_t remove_degenerate_triangles();
  /// The share of the mesh's area (0-1) in triangles whose shading normals do not all stand clear of the
  /// triangle's plane on one side: some vertex normal within about 6° of the plane (|cos| to the face normal below
  /// 0.1), or normals on both sides. Rimu ends paths that leave an opaque surface below its geometric plane, so a
  /// diffuse lobe around such a normal loses up to half of its light (pbrt-v4 follows those paths through the
  /// surface): what that changes in an image goes with the area, not the number of triangles (a scanned mesh's
  /// slivers are many and small). 0 for meshes without normals.
  double normals_near_plane_area_share() const;
  /// Warnings about normals near the plane are given from this share of a mesh's area (1 %): a few such triangles
  /// are a crease or a sliver, 1 % of the area or more is how the mesh was made (a floor whose normals lie along it).
  static constexpr double kNormalsNearPlaneWarningShare = 0.01;
  /// How many vertices have the normal (0, 0, 0) ("no normal here"), 0 for meshes without normals.
  size_t vertices_without_normal() const;
  /// Checks indices are in range and every number is finite; returns an empty string or what is wrong.
  std::string validate() const;
};

}  // namespace rimu
