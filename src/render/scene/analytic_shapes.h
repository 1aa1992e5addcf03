// Quadrics and boxes as triangle meshes, with the analytic shape's normals and pbrt-v4's (u, v) at the vertices:
// the JSON shapes "box", "cylinder", "disk" and the pbrt importer's cylinder, disk and partial sphere share them.
//
// Why meshes rather than Embree user geometry: an emissive shape must be an AreaLight, which samples triangles (the
// light tree, spherical-triangle sampling, power from the area), and instancing, alpha and medium interfaces all
// work on meshes already. The cost is a bounded geometric error, the same for every size (relative to the radius):
//   - the angle is cut into steps of at most 2π/96 (3.75°), the sphere's polar angle into steps of at most π/48;
//   - every vertex lies on the surface, so a circle's chord sags by at most 1 − cos(π/96) = 5.4e-4 of the radius
//     (the silhouette of a cylinder or disk) and a sphere's mesh by at most 1.1e-3 of the radius (the middle of a
//     cell, where both chords sag);
//   - areas are short by at most 7.2e-4 (a disk's sectors: 1 − sin Δ/Δ), 1.8e-4 (a cylinder's side: 1 −
//     sin(Δ/2)/(Δ/2)) and 9e-4 (a sphere) of the true area: under 1e-3 for every shape, and so is an emitter's
//     power, spread over the mesh's area (tests/render/analytic_shapes_test.cpp measures them).
// The shading normals are the analytic ones, so reflections do not facet.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "render/scene/triangle_mesh.h"

namespace rimu {

/// A mesh of these shapes in double precision: the pbrt importer writes it into the scene document as it is (so the
/// document holds pbrt's surface to double precision), and the JSON shapes round it to Rimu's float TriangleMesh.
/// Indices are counter-clockwise seen from the front (where the normals point).
struct AnalyticMesh {
  std::vector<std::array<double, 3>> positions, normals;
  std::vector<std::array<double, 2>> uvs;
  std::vector<uint32_t> indices;

  size_t triangle_count() const { return indices.size() / 3; }
  TriangleMesh to_triangle_mesh() const;
};

/// The steps a circular arc of `angle` radians is cut into: at most 2π/96 each, at least one.
int arc_segments(double angle_rad);

/// pbrt-v4's cylinder: x = r cos φ, y = r sin φ, z in [zmin, zmax], φ in [0, φmax]; u = φ/φmax, v = (z − zmin)/(zmax −
/// zmin); normals point away from the axis; area r·φmax·(zmax − zmin). Open at both ends. Needs radius > 0, zmin <
/// zmax, 0 < φmax ≤ 2π.
AnalyticMesh cylinder_mesh(double radius, double zmin, double zmax, double phimax_rad);

/// pbrt-v4's disk (an annulus sector) in the plane z = height: r in [inner, radius], φ in [0, φmax]; u = φ/φmax, v =
/// (radius − r)/(radius − inner); normal +z; area φmax/2·(radius² − inner²). Needs 0 ≤ inner < radius, 0 < φmax ≤ 2π.
AnalyticMesh disk_mesh(double height, double radius, double inner_radius, double phimax_rad);

/// pbrt-v4's (partial) sphere about the origin: z in [zmin, zmax] (clamped to ±radius), φ in [0, φmax]; u = φ/φmax,
/// v = (θ − θ(zmin))/(θ(zmax) − θ(zmin)) with θ the polar angle from +z; normals outward; area r·φmax·(zmax − zmin).
/// A pole inside the range gets one vertex per column (at the column's middle u), so uv does not pinch there.
/// Needs radius > 0, zmin < zmax after clamping, 0 < φmax ≤ 2π.
AnalyticMesh sphere_mesh(double radius, double zmin, double zmax, double phimax_rad);

/// The axis-aligned box [lo, hi]: 12 triangles, outward face normals, each face's uv (0,0)-(1,1) across it along
/// the axes listed in docs/scene-format.md (u × v = the outward normal). Needs lo < hi on every axis.
AnalyticMesh box_mesh(const Vec3& lo, const Vec3& hi);

/// Appends `part` to `mesh` (both with normals and uvs, or both without).
void append_mesh(AnalyticMesh& mesh, const AnalyticMesh& part);
/// Turns a mesh inside out: the winding and the normals are flipped (uvs kept).
void flip_mesh(AnalyticMesh& mesh);

}  // namespace rimu
