// Loop subdivision of a triangle mesh (C. Loop, "Smooth Subdivision Surfaces Based on Triangles", MS thesis,
// University of Utah, 1987), as pbrt-v4's "loopsubdiv" shape asks for: `levels` 1-to-4 splits, then every vertex
// moved to its limit position, with the limit surface's normal there.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rimu {

struct LoopMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<double, 3>> normals;  ///< unit limit normals, on the side the triangles' winding faces
  std::vector<uint32_t> indices;               ///< 3 per triangle, wound as the control mesh's
};

/// Subdivides `levels` times and moves the vertices to the limit surface.
/// Rules (each a weighted sum of the level's points):
/// - a new vertex on an interior edge (a, b) with opposite vertices c, d: 3/8 (a + b) + 1/8 (c + d); on a boundary
///   edge: 1/2 (a + b);
/// - an old interior vertex v of valence n: (1 − nβ) v + β Σ neighbours, with Warren's β = 3/16 for n = 3 and
///   3/(8n) otherwise (as pbrt); an old boundary vertex: 3/4 v + 1/8 (its two boundary neighbours), the cubic
///   B-spline rule, so boundaries are B-spline curves of the boundary polygon and meet the neighbouring patch;
/// - limit positions: interior (1 − nγ) v + γ Σ neighbours with γ = 1/(n + 3/(8β)) (the left eigenvector of the
///   vertex rule); boundary (b₀ + 4v + b₁)/6, the cubic B-spline's limit (pbrt-v4 uses 1/5, 3/5, 1/5 there);
/// - limit normals: the cross product of the two limit tangents, interior Σ cos(2πi/n) qᵢ × Σ sin(2πi/n) qᵢ over the
///   ordered ring, boundary along-curve q₀ − qₙ₋₁ and across-curve masks of Hoppe et al. 1994 ("Piecewise smooth
///   surface reconstruction", SIGGRAPH), turned to the side the ring's triangles face.
/// Closed meshes stay closed: every edge of the result is shared by the same two triangles it would be in the
/// control mesh's refinement. Throws std::invalid_argument for an edge of more than two triangles, an edge two
/// triangles wind the same way (inconsistent orientation), a vertex where separate fans meet, or levels outside
/// 0-10; std::length_error if the result would exceed `max_triangles`.
LoopMesh loop_subdivide(const std::vector<std::array<double, 3>>& positions, const std::vector<uint32_t>& indices, int levels,
                        std::size_t max_triangles = std::size_t(1) << 27);

}  // namespace rimu
