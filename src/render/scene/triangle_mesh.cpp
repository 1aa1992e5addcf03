#include "render/scene/triangle_mesh.h"

#include <cmath>
#include <utility>
#include <vector>

namespace rimu {

void TriangleMesh::transform(const Transform& t) {
  for (Vec3& p : positions) p = t.point(p);
  for (Vec3& n : normals) {
    const Vec3 m = t.normal(n);
    const float len = length(m);
    n = len > 0.0f ? m / len : n;
  }
  if (t.determinant() < 0.0f) {
    for (size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
    // The swap moves pbrt's default uvs with their vertices.
    if (default_uvs == DefaultUvs::pbrt) default_uvs = DefaultUvs::pbrt_swapped;
    else if (default_uvs == DefaultUvs::pbrt_swapped) default_uvs = DefaultUvs::pbrt;
  }
}

size_t TriangleMesh::remove_degenerate_triangles() {
  std::vector<uint32_t> kept;
  kept.reserve(indices.size());
  size_t removed = 0;
  for (size_t i = 0; i + 2 < indices.size(); i += 3) {
    const Vec3 a = positions[indices[i]], b = positions[indices[i + 1]], c = positions[indices[i + 2]];
    const float area2 = length(cross(b - a, c - a));
    if (area2 > 0.0f && std::isfinite(area2)) {
      kept.insert(kept.end(), {indices[i], indices[i + 1], indices[i + 2]});
    } else {
      ++removed;
    }
  }
  indices = std::move(kept);
  return removed;
}

double TriangleMesh::normals_near_plane_area_share() const {
  constexpr float kClearCos = 0.1f;  // cos 84°: a normal 6° or less from the plane is "in" it
  if (normals.size() != positions.size()) return 0;
  double near_area2 = 0, area2 = 0;  // twice the areas
  for (size_t i = 0; i + 2 < indices.size(); i += 3) {
    const Vec3 a = positions[indices[i]], b = positions[indices[i + 1]], c = positions[indices[i + 2]];
    const Vec3 g = cross(b - a, c - a);
    const float g_length = length(g);
    if (!(g_length > 0.0f) || !std::isfinite(g_length)) continue;  // degenerate: removed elsewhere
    area2 += g_length;
    int above = 0, below = 0, without = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3 n = normals[indices[i + size_t(k)]];
      const float n_length = length(n);
      if (!(n_length > 0.0f)) {
        ++without;  // no normal at this corner: the triangle is shaded flat (normals), nothing lies in its plane
        continue;
      }
      const float cos_to_face = dot(n, g) / (n_length * g_length);
      above += cos_to_face > kClearCos;
      below += cos_to_face < -kClearCos;
    }
    if (without == 0 && above != 3 && below != 3) near_area2 += g_length;
  }
  return area2 > 0 ? near_area2 / area2 : 0.0;
}

std::string TriangleMesh::validate() const {
  if (indices.size() % 3 != 0) return "the index count is not a multiple of 3";
  if (!normals.empty() && normals.size() != positions.size())
    return "there are " + std::to_string(normals.size()) + " normals for " + std::to_string(positions.size()) +
           " vertices";
  if (!uvs.empty() && uvs.size() != positions.size())
    return "there are " + std::to_string(uvs.size()) + " uvs for " + std::to_string(positions.size()) + " vertices";
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= positions.size())
      return "index " + std::to_string(indices[i]) + " (triangle " + std::to_string(i / 3) + ") is out of range: " +
             std::to_string(positions.size()) + " vertices";
  for (size_t i = 0; i < positions.size(); ++i)
    if (!is_finite(positions[i])) return "vertex " + std::to_string(i) + " is not finite";
  for (size_t i = 0; i < normals.size(); ++i)
    if (!is_finite(normals[i])) return "normal " + std::to_string(i) + " is not finite";
  return {};
}

size_t TriangleMesh::vertices_without_normal() const {
  size_t count = 0;
  for (const Vec3& n : normals) count += length_squared(n) == 0.0f;
  return count;
}

size_t TriangleMesh::turn_to_pbrt_front(bool reversed) {
  if (reversed)
    for (Vec3& n : normals) n = -n;
  std::vector<uint8_t> flips(triangle_count(), 0);
  size_t flipped = 0;
  for (size_t t = 0; t < triangle_count(); ++t) {
    const uint32_t* tri = &indices[3 * t];
    bool flip = reversed;
    if (!normals.empty()) {
      const Vec3 a = normals[tri[0]], b = normals[tri[1]], c = normals[tri[2]];
      if (dot(a, a) > 0.0f && dot(b, b) > 0.0f && dot(c, c) > 0.0f) {
        const Vec3 g = cross(positions[tri[1]] - positions[tri[0]], positions[tri[2]] - positions[tri[0]]);
        flip = dot(g, a + b + c) < 0.0f;
      }
    }
    flips[t] = flip;
    flipped += flip;
  }
  if (flipped == 0) return 0;
  if (uvs.empty() && default_uvs != DefaultUvs::barycentric) {
    // Per-corner vertices carrying the default uvs of the order read, before corners 1 and 2 trade places.
    const Vec2 corner_uv[3] = {{0, 0}, {1, 0}, {1, 1}};
    std::vector<Vec3> corner_positions, corner_normals;
    std::vector<uint32_t> corner_indices;
    corner_positions.reserve(indices.size());
    for (size_t i = 0; i < indices.size(); ++i) {
      corner_indices.push_back(uint32_t(i));
      corner_positions.push_back(positions[indices[i]]);
      if (!normals.empty()) corner_normals.push_back(normals[indices[i]]);
      uvs.push_back(corner_uv[i % 3]);
    }
    if (default_uvs == DefaultUvs::pbrt_swapped)  // (0,0), (1,1), (1,0) at corners 0, 1, 2
      for (size_t i = 0; i < uvs.size(); i += 3) std::swap(uvs[i + 1], uvs[i + 2]);
    positions = std::move(corner_positions);
    normals = std::move(corner_normals);
    indices = std::move(corner_indices);
  }
  for (size_t t = 0; t < triangle_count(); ++t)
    if (flips[t]) std::swap(indices[3 * t + 1], indices[3 * t + 2]);
  return flipped;
}

}  // namespace rimu
