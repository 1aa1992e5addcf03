#include "render/scene/curve_set.h"
#include "render/scene/curve_self_hit.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rimu {
namespace {

CurveControlPoint lerp(const CurveControlPoint& a, const CurveControlPoint& b, float t) {
  return {a.position * (1.0f - t) + b.position * t, a.radius * (1.0f - t) + b.radius * t};
}

// Σ w_i·p_i of positions and radii alike: every conversion below is such a fixed affine combination.
CurveControlPoint combine(std::initializer_list<std::pair<float, const CurveControlPoint*>> terms) {
  CurveControlPoint out{Vec3{}, 0.0f};
  for (const auto& [w, p] : terms) {
    out.position = out.position + p->position * w;
    out.radius += p->radius * w;
  }
  return out;
}

// Any unit vector perpendicular to the unit `n`.
Vec3 perpendicular(Vec3 n) {
  const Vec3 other = std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalize(cross(n, other));
}

}  // namespace

CurveSample evaluate_bezier(const CurveControlPoint* cp, float t) {
  const CurveControlPoint a0 = lerp(cp[0], cp[1], t), a1 = lerp(cp[1], cp[2], t), a2 = lerp(cp[2], cp[3], t);
  const CurveControlPoint b0 = lerp(a0, a1, t), b1 = lerp(a1, a2, t);
  const CurveControlPoint c = lerp(b0, b1, t);
  // A cubic's derivative is 3 × the difference of the last de Casteljau pair.
  return {c.position, (b1.position - b0.position) * 3.0f, c.radius};
}

Vec3 slerp_unit(Vec3 a, Vec3 b, float t) {
  const float cos_theta = std::clamp(dot(a, b), -1.0f, 1.0f);
  const float theta = std::acos(cos_theta);
  if (theta < 1e-4f) return normalize(a * (1.0f - t) + b * t);
  // The unit vector perpendicular to a in the plane of a and b (any perpendicular for opposite normals, where the
  // plane is not defined).
  Vec3 towards_b = b - a * cos_theta;
  towards_b = length_squared(towards_b) > 1e-12f ? normalize(towards_b) : perpendicular(a);
  return a * std::cos(theta * t) + towards_b * std::sin(theta * t);
}

size_t curve_segment_count(size_t points, CurveBasis basis, int degree) {
  if ((degree != 2 && degree != 3) || points < size_t(degree) + 1) return 0;
  if (basis == CurveBasis::bspline) return points - size_t(degree);
  return (points - 1) % size_t(degree) == 0 ? (points - 1) / size_t(degree) : 0;
}

size_t append_curve(CurveSet& set, std::span<const Vec3> points, std::span<const float> radii, CurveBasis basis,
                    int degree, std::span<const Vec3> segment_normals) {
  const size_t segments = curve_segment_count(points.size(), basis, degree);
  if (segments == 0 || radii.size() != points.size())
    throw std::invalid_argument("the control points do not make whole segments");
  if (set.kind == CurveKind::ribbon && segment_normals.size() != segments + 1)
    throw std::invalid_argument("a ribbon needs a normal at each segment's ends");
  std::vector<CurveControlPoint> p(points.size());
  for (size_t i = 0; i < p.size(); ++i) p[i] = {points[i], radii[i]};
  size_t dropped = 0;
  for (size_t k = 0; k < segments; ++k) {
    std::array<CurveControlPoint, 4> b;
    if (basis == CurveBasis::bezier && degree == 3) {
      std::copy_n(&p[3 * k], 4, b.begin());
    } else {
      // The quadratic Bézier (q0, q1, q2) of this segment: a quadratic B-spline's segment over P_k … P_k+2 is the
      // Bézier of (P_k + P_k+1)/2, P_k+1, (P_k+1 + P_k+2)/2.
      std::array<CurveControlPoint, 3> q;
      if (basis == CurveBasis::bezier && degree == 2) {
        q = {p[2 * k], p[2 * k + 1], p[2 * k + 2]};
      } else if (degree == 2) {
        q = {combine({{0.5f, &p[k]}, {0.5f, &p[k + 1]}}), p[k + 1], combine({{0.5f, &p[k + 1]}, {0.5f, &p[k + 2]}})};
      }
      if (degree == 2) {
        // Degree elevation: the same quadratic written with 4 points, q0, (q0 + 2q1)/3, (2q1 + q2)/3, q2.
        b = {q[0], combine({{1.0f / 3, &q[0]}, {2.0f / 3, &q[1]}}), combine({{2.0f / 3, &q[1]}, {1.0f / 3, &q[2]}}), q[2]};
      } else {
        // A uniform cubic B-spline's segment over P0 … P3 is the Bézier of (P0 + 4P1 + P2)/6, (2P1 + P2)/3,
        // (P1 + 2P2)/3, (P1 + 4P2 + P3)/6 (the basis change of the uniform knot vector).
        const CurveControlPoint* s = &p[k];
        b = {combine({{1.0f / 6, &s[0]}, {4.0f / 6, &s[1]}, {1.0f / 6, &s[2]}}),
             combine({{2.0f / 3, &s[1]}, {1.0f / 3, &s[2]}}), combine({{1.0f / 3, &s[1]}, {2.0f / 3, &s[2]}}),
             combine({{1.0f / 6, &s[1]}, {4.0f / 6, &s[2]}, {1.0f / 6, &s[3]}})};
      }
    }
    const bool no_width = std::all_of(b.begin(), b.end(), [](const CurveControlPoint& c) { return !(c.radius > 0); });
    const bool one_point =
        std::all_of(b.begin(), b.end(), [&](const CurveControlPoint& c) { return c.position == b[0].position; });
    if (no_width || one_point) {
      ++dropped;
      continue;
    }
    set.first_point.push_back(uint32_t(set.points.size()));
    set.points.insert(set.points.end(), b.begin(), b.end());
    set.u_start.push_back(float(double(k) / double(segments)));
    set.u_length.push_back(float(1.0 / double(segments)));
    if (set.kind == CurveKind::ribbon) {
      // pbrt-v4 turns a ribbon's normal from n0 to n1 along the segment by spherical interpolation. Embree orients
      // a ribbon by a cubic Bézier of normals, which cannot follow an arc of a circle exactly: the control normals
      // are those of the cubic through the arc's values at t = 0, ⅓, ⅔, 1: within 0.08° of the arc for a quarter
      // turn and 0.9° for 150°, where a straight blend of n0 and n1 strays 4° and 26°.
      const Vec3 n0 = normalize(segment_normals[k]), n1 = normalize(segment_normals[k + 1]);
      const Vec3 s0 = n0, s1 = slerp_unit(n0, n1, 1.0f / 3), s2 = slerp_unit(n0, n1, 2.0f / 3), s3 = n1;
      set.normals.push_back(s0);
      set.normals.push_back((s0 * -15.0f + s1 * 54.0f - s2 * 27.0f + s3 * 6.0f) / 18.0f);
      set.normals.push_back((s0 * 6.0f - s1 * 27.0f + s2 * 54.0f - s3 * 15.0f) / 18.0f);
      set.normals.push_back(s3);
    }
  }
  return dropped;
}

void curve_surface(const CurveSet& set, uint32_t segment, float t, Vec3 ray_origin, Vec3 ray_direction, float ray_t,
                   Vec3 embree_normal, SurfaceHit& hit) {
  const uint32_t first = set.first_point[segment];
  const CurveControlPoint* cp = &set.points[first];
  t = std::clamp(t, 0.0f, 1.0f);
  const CurveSample s = evaluate_bezier(cp, t);
  Vec3 dpdt = s.derivative;
  if (!(length_squared(dpdt) > 0.0f)) {
    // Coincident control points stop the parameter at an end (p0 = p1 gives p'(0) = 0): the tangent is then the
    // limit direction, taken from a short chord around t.
    const float t0 = std::max(t - 1e-3f, 0.0f), t1 = std::min(t + 1e-3f, 1.0f);
    dpdt = (evaluate_bezier(cp, t1).position - evaluate_bezier(cp, t0).position) / (t1 - t0);
    if (!(length_squared(dpdt) > 0.0f)) dpdt = cp[3].position - cp[0].position;
    if (!(length_squared(dpdt) > 0.0f)) dpdt = Vec3{1, 0, 0};  // unreachable: one-point segments are not loaded
  }
  const Vec3 tangent = normalize(dpdt);
  const Vec3 d = normalize(ray_direction);
  Vec3 across = cross(d, tangent);
  const float across_length = length(across);
  // Looking along the fibre, "across" is undefined; any side will do for that measure-zero set of rays.
  across = across_length > 1e-6f ? across / across_length : perpendicular(tangent);
  const float radius = s.radius;
  const Vec3 embree_point = ray_origin + ray_direction * ray_t;
  const Vec3 from_centre = embree_point - s.position;
  const float h = radius > 0.0f ? std::clamp(dot(from_centre, across) / radius, -1.0f, 1.0f) : 0.0f;

  Vec3 normal, position, dpdv = across * (2.0f * radius);
  switch (set.kind) {
    case CurveKind::flat: {
      // pbrt-v4's flat curve: the normal is the ray's reverse made perpendicular to the tangent.
      normal = -(d - tangent * dot(tangent, d));
      normal = length_squared(normal) > 1e-12f ? normalize(normal) : cross(tangent, across);
      position = s.position + across * (h * radius);
      break;
    }
    case CurveKind::cylinder: {
      const Vec3 radial = from_centre - tangent * dot(from_centre, tangent);
      const float radial_length = length(radial);
      normal = normalize(embree_normal);
      if (!is_finite(normal)) normal = radial_length > 0.0f ? radial / radial_length : -d;
      if (dot(normal, radial) < 0.0f) normal = -normal;  // the tube's outside
      position = radial_length > 0.0f ? s.position + radial * (radius / radial_length) : embree_point;
      break;
    }
    case CurveKind::ribbon: {
      const Vec3* n = &set.normals[first];
      const Vec3 a0 = n[0] * (1 - t) + n[1] * t, a1 = n[1] * (1 - t) + n[2] * t, a2 = n[2] * (1 - t) + n[3] * t;
      const Vec3 interpolated = (a0 * (1 - t) + a1 * t) * (1 - t) + (a1 * (1 - t) + a2 * t) * t;
      Vec3 width_direction = cross(interpolated, tangent);
      const float width_length = length(width_direction);
      width_direction = width_length > 1e-12f ? width_direction / width_length : across;
      normal = normalize(embree_normal);
      if (!is_finite(normal)) normal = normalize(cross(tangent, width_direction));
      if (dot(normal, interpolated) < 0.0f) normal = -normal;  // the side the ribbon's own normals give
      position = s.position + width_direction * dot(from_centre, width_direction);
      dpdv = width_direction * (2.0f * radius);
      break;
    }
  }
  float scale = 0.0f, max_radius = 0.0f;
  for (int i = 0; i < 4; ++i) {
    scale = std::max(scale, max_component(abs(cp[i].position)));
    max_radius = std::max(max_radius, cp[i].radius);
  }
  if (is_finite(position)) {
    hit.position = position;
    hit.position_scale = scale + max_radius;
  }
  hit.geometric_normal = normal;
  hit.shading_normal = normal;
  hit.uv = {set.u_start[segment] + t * set.u_length[segment], 0.5f * (1.0f + h)};
  hit.dpdu = dpdt / set.u_length[segment];
  hit.dpdv = dpdv;
}

bool is_self_hit(const CurveSet& set, uint32_t segment, float t, Vec3 ray_origin, float ray_t) {
  const CurveSample s = evaluate_bezier(&set.points[set.first_point[segment]], std::clamp(t, 0.0f, 1.0f));
  // The slack covers offset_ray_origin's lift (2⁻¹⁸ of the coordinates' magnitude) with room to spare.
  const float slack = 0x1p-14f * (max_component(abs(s.position)) + s.radius);
  return ray_t <= 4.0f * s.radius + slack && length(ray_origin - s.position) <= 2.0f * s.radius + slack;
}

bool leaves_cylinder(const CurveSet& set, uint32_t segment, float t, Vec3 ray_origin, Vec3 ray_direction, float ray_t) {
  if (set.kind != CurveKind::cylinder) return false;
  const CurveSample s = evaluate_bezier(&set.points[set.first_point[segment]], std::clamp(t, 0.0f, 1.0f));
  if (!(length_squared(s.derivative) > 0.0f)) return false;
  const Vec3 tangent = normalize(s.derivative);
  const Vec3 from_axis = ray_origin + ray_direction * ray_t - s.position;
  return dot(from_axis - tangent * dot(from_axis, tangent), ray_direction) > 0.0f;
}

int curve_tessellation_rate(const CurveSet& set) {
  constexpr int kDefault = 4, kMost = 64;
  constexpr float kTolerance = 0.05f;  // of the segment's smallest radius
  double most = kDefault;
  for (const uint32_t first : set.first_point) {
    const CurveControlPoint* p = &set.points[first];
    const float second = 6.0f * std::max(length(p[0].position - p[1].position * 2.0f + p[2].position),
                                         length(p[1].position - p[2].position * 2.0f + p[3].position));
    const float radius = std::min({p[0].radius, p[1].radius, p[2].radius, p[3].radius});
    if (!(radius > 0.0f)) continue;
    most = std::max(most, std::ceil(std::sqrt(double(second) / (8.0 * kTolerance * radius))));
    if (most >= kMost) return kMost;
  }
  return int(most);
}

}  // namespace rimu
