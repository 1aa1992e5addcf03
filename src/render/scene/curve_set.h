// Thin curves (hair, fur, grass): cubic Bézier segments with a radius per control point, as Embree's native curve
// primitives take them, and what a ray's hit on one means to a material.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "transport/geometry/surface_hit.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// How the curve's cross-section meets a ray (pbrt-v4's curve "type"; Embree's curve kinds).
enum class CurveKind {
  flat,      ///< a ribbon that always faces the ray (Embree's FLAT curve; pbrt "flat")
  cylinder,  ///< a round tube swept by a circle (Embree's ROUND curve; pbrt "cylinder")
  ribbon,    ///< a ribbon turned by per-point normals (Embree's NORMAL_ORIENTED curve; pbrt "ribbon")
};
/// The control points' basis (pbrt-v4's "basis"): Bézier (the curve passes through every degree-th point) or
/// uniform B-spline (it passes through none in general, and is C^(degree−1) across segments).
enum class CurveBasis { bezier, bspline };

/// One control point of a cubic Bézier segment: position and radius, the layout of Embree's RTC_FORMAT_FLOAT4
/// vertex (x, y, z, r).
struct CurveControlPoint {
  Vec3 position;
  float radius = 0;
};

/// The curve at a parameter of one segment.
struct CurveSample {
  Vec3 position;    ///< on the centreline
  Vec3 derivative;  ///< ∂p/∂t, t the segment's own parameter in [0, 1]
  float radius = 0;
};

/// A cubic Bézier segment at t in [0, 1] (de Casteljau's scheme: stable for any t in range).
CurveSample evaluate_bezier(const CurveControlPoint* segment, float t);

/// Many curves of one kind, as cubic Bézier segments of 4 control points each (points 4s … 4s + 3 are segment s:
/// a converted curve shares no points between segments, which keeps a B-spline's conversion local). 64 bytes of
/// control points, 12 of bookkeeping per segment (+ 48 of normals for ribbons).
struct CurveSet {
  CurveKind kind = CurveKind::flat;
  std::vector<CurveControlPoint> points;
  std::vector<uint32_t> first_point;  ///< 4s per segment s: Embree's index buffer
  /// The segment's span of its curve's parameter: u = u_start + t·u_length, u in [0, 1] along the whole curve.
  std::vector<float> u_start, u_length;
  std::vector<Vec3> normals;  ///< ribbons: one per control point (a cubic Bézier of normals), else empty
  size_t segments() const { return first_point.size(); }
};

/// The linear pieces per segment Embree should cut `set`'s flat curves into (rtcSetGeometryTessellationRate, default
/// 4): enough that the chord of a piece strays from the segment by at most 5 % of its smallest radius, in [4, 64].
/// A cubic Bézier's distance from its piecewise-linear interpolant with n pieces is at most max|B''|/(8n²), with
/// |B''| ≤ 6·max(|P0 − 2P1 + P2|, |P1 − 2P2 + P3|). Hair (short, nearly straight segments) keeps 4; a long
/// bent curve of a few pixels' width (pbrt-v3-scenes' figures/f3-18) needs ~46.
int curve_tessellation_rate(const CurveSet& set);

/// The unit vector a fraction t of the way from unit `a` to unit `b` along the great circle through them (spherical
/// interpolation; pbrt-v4's Slerp). Opposite vectors turn about an arbitrary perpendicular.
Vec3 slerp_unit(Vec3 a, Vec3 b, float t);

/// The number of segments a curve of `points` control points has in `basis` and `degree` (2 or 3), or 0 when the
/// count does not make whole segments (Bézier: degree·n + 1 points; B-spline: n + degree points).
size_t curve_segment_count(size_t points, CurveBasis basis, int degree);

/// Appends one curve to `set` as cubic Bézier segments: a B-spline is converted exactly (each segment's Bézier
/// points are fixed averages of its degree + 1 B-spline points) and a quadratic raised exactly to a cubic (degree
/// elevation), radii alongside the positions (so the radius is the same spline of the per-point radii).
/// `segment_normals` (ribbons): segments + 1 normals, one at each segment's ends, turned from one to the next along
/// the arc between them (slerp_unit, as pbrt-v4 does), to within Embree's cubic Bézier of normals.
/// Segments of zero radius or a single point (nothing a ray can hit) are left out; the number left out is returned.
/// Throws std::invalid_argument when the count of points does not make whole segments.
size_t append_curve(CurveSet& set, std::span<const Vec3> points, std::span<const float> radii, CurveBasis basis,
                    int degree, std::span<const Vec3> segment_normals = {});

/// Where a ray that Embree reports hitting segment `segment` at its parameter t lies on the fibre, written into
/// `hit` (SurfaceHit's contract for curves, docs/scene-format.md "curves"):
/// - uv = (u along the whole curve, v across it): v = (1 + h)/2 with h the signed offset of the hit from the
///   centreline along d × ∂p/∂u (perpendicular to both the ray and the tangent), over the local radius, in [−1, 1];
/// - dpdu = ∂p/∂u, never zero; dpdv = ∂p/∂v across the fibre (2r along d × ∂p/∂u, or across a ribbon);
/// - normals: flat, facing the ray (perpendicular to the tangent); cylinder, the tube's own; ribbon, the ribbon's;
/// - position put back on the fibre from the control points (its error is theirs, position_scale), not o + t·d.
/// `embree_normal`: Embree's unnormalised Ng (used for cylinders and ribbons).
void curve_surface(const CurveSet& set, uint32_t segment, float t, Vec3 ray_origin, Vec3 ray_direction,
                   float ray_t, Vec3 embree_normal, SurfaceHit& hit);

/// Whether a candidate hit at distance `ray_t` on `segment` at t is the fibre the ray is leaving: the origin lies
/// on that fibre (within twice its radius of the centreline there) and the hit within four radii of it. A flat
/// curve turns to face every ray, so a ray leaving one would meet it again at once; a transmitted ray would meet a
/// tube's far side. Both are the same fibre, which a fibre's BSDF already accounts for whole.
bool is_self_hit(const CurveSet& set, uint32_t segment, float t, Vec3 ray_origin, float ray_t);

}  // namespace rimu
