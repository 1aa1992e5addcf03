// Directions uniform in the solid angle a triangle subtends at a point (Arvo 1995, "Stratified sampling of
// spherical triangles", SIGGRAPH '95). Area lights use it where a triangle is close to the point it lights: there
// uniform area sampling, whose solid-angle density d²/(A cos θ_l) varies without bound across the triangle, gives
// estimates whose variance grows as A/d² (without bound for a point that touches the emitter), whereas a direction
// uniform in solid angle leaves only the receiver's cosine to vary.
//
// The spherical triangle's corners are the unit vectors a, b, c from the point to the vertices; its solid angle is
// the angle excess Ω = α + β + γ − π (Girard), α the interior angle at a between the great arcs to b and to c,
// evaluated as Van Oosterom and Strackee's tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a) (one atan2). Arvo's
// inversion picks the sub-triangle (a, b, ĉ) of area u₁·Ω (ĉ on the arc from a to c), then a point on the arc from b
// to ĉ with 1 − cos of its angle from b uniform (u₂), which makes the density exactly 1/Ω. Everything is computed in
// double from the corners relative to the point: α by atan2 of the tangent vectors, so that thin triangles keep their
// precision.
#pragma once

#include <optional>

#include "transport/geometry/vector.h"

namespace rimu {

/// Ω of the triangle (v0, v1, v2) seen from p, in steradians; 0 when p lies in the triangle's plane.
double spherical_triangle_solid_angle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2);

/// A unit direction from p uniform in the triangle's solid angle (density 1/Ω, Ω as above), or std::nullopt when
/// Ω is not positive (p in the triangle's plane) or not finite. With solid_angle_sr, also writes Ω there (the same
/// value spherical_triangle_solid_angle returns), so that a caller needs not compute it twice.
std::optional<Vec3> sample_spherical_triangle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2, Vec2 u,
                                              double* solid_angle_sr = nullptr);

}  // namespace rimu
