// Clarberg's equal-area mapping between the unit square and the unit sphere ("Fast Equal-Area Mapping of the
// (Hemi)Sphere using SIMD", JGT 13(3), 2008), in the orientation pbrt-v4 gives it for its environment maps
// (PBR 4th ed., §3.8.3 "Equal-Area Mapping").
//
// The square [0, 1]² is folded like an octahedron: with (a, b) = (2u − 1, 2v − 1) and r = 1 − |1 − |a| − |b||,
//   z = ±(1 − r²)           (+ inside the diamond |a| + |b| < 1, − in the four corners),
//   φ = (π/4)·((|b| − |a|)/r + 1) in the quadrant of (a, b),   x, y = r·√(2 − r²)·(cos φ, sin φ),
// so the centre (½, ½) is +z, the middles of the right and top edges are +x and +y, and the four corners are −z.
// The map preserves area: a region of the square of area A covers a solid angle 4π·A. That makes a square image
// whose pixels all subtend 4π/(width·height) steradians, so importance sampling by pixel has a constant Jacobian.
#pragma once

#include "transport/geometry/vector.h"

namespace rimu {

/// The unit direction of square point `p` ∈ [0, 1]² (values outside are clamped).
Vec3 equal_area_square_to_sphere(Vec2 p);

/// The square point of direction `d` (need not be normalised; not zero), in [0, 1]². The inverse of
/// equal_area_square_to_sphere up to rounding and the 1.3e-7 rad of its polynomial atan (equal_area_square.cpp).
Vec2 equal_area_sphere_to_square(Vec3 d);

}  // namespace rimu
