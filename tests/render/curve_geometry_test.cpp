// Curves (render/scene/curve_set.h) through Embree: the area they cover, their widths, and what a hit reports
// (u along the curve, h across it, ∂p/∂u, normals), checked against the straight fibre's own geometry.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/scene/embree_scene.h"

using namespace rimu;

namespace {

Ray ray_from(Vec3 origin, Vec3 direction) {
  Ray r;
  r.origin = origin;
  r.direction = normalize(direction);
  r.t_min = 0.0f;
  r.t_max = 1e30f;
  return r;
}

// A straight fibre along x from −L/2 to L/2 at z = 0, as one curve of `segments` cubic Bézier segments with evenly
// spaced control points (so u runs uniformly along it), full width growing linearly from w0 to w1.
CurveSet straight_fibre(CurveKind kind, float length, float w0, float w1, int segments = 1) {
  CurveSet set;
  set.kind = kind;
  std::vector<Vec3> points;
  std::vector<float> radii;
  const int count = 3 * segments + 1;
  for (int i = 0; i < count; ++i) {
    const float u = float(i) / float(count - 1);
    points.push_back({length * (u - 0.5f), 0.0f, 0.0f});
    radii.push_back(0.5f * (w0 + (w1 - w0) * u));
  }
  std::vector<Vec3> normals(size_t(segments) + 1, Vec3{0, 0, 1});
  append_curve(set, points, radii, CurveBasis::bezier, 3, kind == CurveKind::ribbon ? std::span<const Vec3>(normals) : std::span<const Vec3>{});
  return set;
}

// The fraction of a grid of rays straight down (−z), one per cell centre over [−a, a] × [−b, b], that hit, times the
// grid's area: the area the curve covers seen from above.
double covered_area(const EmbreeScene& scene, float a, float b, int nx, int ny) {
  int hits = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const float x = -a + 2 * a * (float(i) + 0.5f) / float(nx), y = -b + 2 * b * (float(j) + 0.5f) / float(ny);
      if (scene.intersect(ray_from({x, y, 1.0f}, {0, 0, -1}))) ++hits;
    }
  return double(hits) / double(nx * ny) * (4.0 * double(a) * double(b));
}

}  // namespace

TEST_CASE("curve: a flat straight fibre seen side-on covers length x width") {
  // L·w = 0.1 m²; the grid's cells are 2 mm × 0.5 mm, so each of the fibre's four edges can be off by at most half a
  // cell: |error| ≤ 2·(0.1·0.00025) + 2·(1·0.00025)... ≤ 0.6 % of the area.
  EmbreeScene scene;
  scene.add_curves(straight_fibre(CurveKind::flat, 1.0f, 0.1f, 0.1f), 0);
  scene.commit();
  CHECK(covered_area(scene, 0.6f, 0.1f, 600, 400) == doctest::Approx(0.1).epsilon(0.006));
}

TEST_CASE("curve: width runs linearly from width0 to width1") {
  EmbreeScene scene;
  scene.add_curves(straight_fibre(CurveKind::flat, 1.0f, 0.05f, 0.15f), 0);
  scene.commit();
  // A trapezoid: L·(w0 + w1)/2 = 0.1 m².
  CHECK(covered_area(scene, 0.6f, 0.1f, 600, 400) == doctest::Approx(0.1).epsilon(0.006));
  // At u = 0.25 the radius is (0.05 + 0.25·0.1)/2 = 0.0375: rays 2 % inside hit, 2 % outside miss.
  for (const float sign : {-1.0f, 1.0f}) {
    CHECK(scene.intersect(ray_from({-0.25f, sign * 0.0375f * 0.98f, 1.0f}, {0, 0, -1})));
    CHECK_FALSE(scene.intersect(ray_from({-0.25f, sign * 0.0375f * 1.02f, 1.0f}, {0, 0, -1})));
  }
}

TEST_CASE("curve: a hit's u along the whole curve, h across it, dp/du along the tangent, normals") {
  const float length = 2.0f, width = 0.2f, radius = 0.1f;
  for (const CurveKind kind : {CurveKind::flat, CurveKind::cylinder, CurveKind::ribbon}) {
    CAPTURE(int(kind));
    EmbreeScene scene;
    scene.set_surface_tangents(false);  // curves set ∂p/∂u regardless: a fibre's BSDF is built around it
    scene.add_curves(straight_fibre(kind, length, width, width, 2), 0);
    scene.commit();
    for (const float x : {-0.7f, -0.2f, 0.4f, 0.9f})
      for (const float h : {-0.9f, -0.5f, 0.0f, 0.3f, 0.8f}) {
        // Looking down −z, d × tangent = (0, −1, 0): h = −y/r (pbrt-v4's sign, v = 1/2 + h/2).
        const float y = -h * radius;
        const auto hit = scene.intersect(ray_from({x, y, 1.0f}, {0, 0, -1}));
        REQUIRE(hit);
        CAPTURE(x);
        CAPTURE(h);
        CHECK(hit->uv.x == doctest::Approx(x / length + 0.5f).epsilon(1e-4));
        CHECK(2.0f * hit->uv.y - 1.0f == doctest::Approx(h).epsilon(1e-3));
        // u spans the whole length: ∂p/∂u = L along x.
        CHECK(hit->dpdu.x == doctest::Approx(length).epsilon(1e-4));
        CHECK(std::fabs(hit->dpdu.y) + std::fabs(hit->dpdu.z) < 1e-4f);
        CHECK(std::fabs(dot(hit->geometric_normal, Vec3{1, 0, 0})) < 1e-4f);
        if (kind == CurveKind::cylinder) {
          // The tube's own normal at height y: (0, y/r, √(1 − (y/r)²)), and the point on its surface.
          const float nz = std::sqrt(1.0f - h * h);
          CHECK(hit->geometric_normal.y == doctest::Approx(-h).epsilon(2e-3));
          CHECK(hit->geometric_normal.z == doctest::Approx(nz).epsilon(2e-3));
          CHECK(hit->position.z == doctest::Approx(radius * nz).epsilon(2e-3));
        } else {
          // A flat fibre faces the ray; the ribbon's normals are +z here: both are +z, and the point lies in z = 0.
          CHECK(hit->geometric_normal.z == doctest::Approx(1.0f).epsilon(1e-5));
          CHECK(std::fabs(hit->position.z) < 1e-6f);
        }
        CHECK(hit->shading_normal.z == doctest::Approx(hit->geometric_normal.z));
      }
  }
}

TEST_CASE("curve: a flat fibre's normal faces an oblique ray and is perpendicular to the tangent") {
  EmbreeScene scene;
  scene.add_curves(straight_fibre(CurveKind::flat, 2.0f, 0.2f, 0.2f), 0);
  scene.commit();
  for (const Vec3 d : {Vec3{0.3f, 0.2f, -1.0f}, Vec3{-0.5f, -0.7f, -0.4f}, Vec3{0.1f, 0.9f, 0.2f}}) {
    const Vec3 target{0.1f, 0.02f, 0.0f};
    const auto hit = scene.intersect(ray_from(target - normalize(d) * 3.0f, d));
    REQUIRE(hit);
    CHECK(dot(hit->geometric_normal, normalize(d)) < 0.0f);
    CHECK(std::fabs(dot(hit->geometric_normal, Vec3{1, 0, 0})) < 1e-5f);
    CHECK(length(hit->geometric_normal) == doctest::Approx(1.0f).epsilon(1e-5));
  }
}

TEST_CASE("curve: a ray leaving a fibre does not stop on that fibre") {
  // A flat fibre turns to face every ray, and a tube's far side lies across it: both would catch the ray that just
  // left it (is_self_hit). Rays from 20 hits, each leaving in 8 directions over both hemispheres, must all escape.
  for (const CurveKind kind : {CurveKind::flat, CurveKind::cylinder}) {
    EmbreeScene scene;
    scene.add_curves(straight_fibre(kind, 2.0f, 0.02f, 0.02f), 0);
    scene.commit();
    int escaped = 0, total = 0;
    for (int k = 0; k < 20; ++k) {
      const float x = -0.9f + 0.09f * float(k), y = 0.0095f * std::sin(float(k));
      const auto hit = scene.intersect(ray_from({x, y, 1.0f}, {0.05f, 0.0f, -1.0f}));
      REQUIRE(hit);
      for (int j = 0; j < 8; ++j) {
        const float phi = 0.785f * float(j);
        const Vec3 out{0.3f * std::cos(phi), std::sin(phi), 0.8f * std::cos(phi) - 0.2f};
        const Vec3 origin = hit->position + hit->geometric_normal * (dot(out, hit->geometric_normal) > 0 ? 1e-6f : -1e-6f);
        ++total;
        if (!scene.intersect(ray_from(origin, out)) && !scene.occluded(ray_from(origin, out))) ++escaped;
      }
    }
    CAPTURE(int(kind));
    CHECK(escaped == total);
  }
}

TEST_CASE("curve: B-spline and quadratic curves become the same curve as Bezier segments") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 2, 0}, {3, 1, 1}, {4, -1, 2}, {6, 0, 1}};
  const std::vector<float> r = {0.1f, 0.2f, 0.15f, 0.05f, 0.3f};
  SUBCASE("cubic B-spline: the uniform basis (1−t)³/6, (3t³ − 6t² + 4)/6, (−3t³ + 3t² + 3t + 1)/6, t³/6") {
    CurveSet set;
    append_curve(set, p, r, CurveBasis::bspline, 3);
    REQUIRE(set.segments() == 2);
    for (size_t k = 0; k < 2; ++k)
      for (const float t : {0.0f, 0.3f, 0.5f, 0.8f, 1.0f}) {
        const float b[4] = {(1 - t) * (1 - t) * (1 - t) / 6, (3 * t * t * t - 6 * t * t + 4) / 6,
                            (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
        Vec3 expected{};
        float expected_r = 0;
        for (size_t i = 0; i < 4; ++i) {
          expected = expected + p[k + i] * b[i];
          expected_r += r[k + i] * b[i];
        }
        const CurveSample s = evaluate_bezier(&set.points[set.first_point[k]], t);
        CHECK(length(s.position - expected) < 1e-5f);
        CHECK(s.radius == doctest::Approx(expected_r).epsilon(1e-5));
        CHECK(set.u_start[k] + t * set.u_length[k] == doctest::Approx((float(k) + t) / 2.0f));
      }
  }
  SUBCASE("quadratic Bezier: (1−t)²q0 + 2t(1−t)q1 + t²q2, raised to a cubic") {
    CurveSet set;
    append_curve(set, p, r, CurveBasis::bezier, 2);
    REQUIRE(set.segments() == 2);
    for (size_t k = 0; k < 2; ++k)
      for (const float t : {0.0f, 0.25f, 0.6f, 1.0f}) {
        const Vec3 expected = p[2 * k] * ((1 - t) * (1 - t)) + p[2 * k + 1] * (2 * t * (1 - t)) + p[2 * k + 2] * (t * t);
        CHECK(length(evaluate_bezier(&set.points[set.first_point[k]], t).position - expected) < 1e-5f);
      }
  }
  SUBCASE("quadratic B-spline: (1−t)²/2, (−2t² + 2t + 1)/2, t²/2") {
    CurveSet set;
    append_curve(set, p, r, CurveBasis::bspline, 2);
    REQUIRE(set.segments() == 3);
    for (size_t k = 0; k < 3; ++k)
      for (const float t : {0.0f, 0.4f, 1.0f}) {
        const Vec3 expected =
            p[k] * ((1 - t) * (1 - t) / 2) + p[k + 1] * ((-2 * t * t + 2 * t + 1) / 2) + p[k + 2] * (t * t / 2);
        CHECK(length(evaluate_bezier(&set.points[set.first_point[k]], t).position - expected) < 1e-5f);
      }
  }
  SUBCASE("point counts that make no whole segments are refused") {
    CurveSet set;
    CHECK(curve_segment_count(3, CurveBasis::bezier, 3) == 0);
    CHECK(curve_segment_count(5, CurveBasis::bezier, 3) == 0);
    CHECK(curve_segment_count(7, CurveBasis::bezier, 3) == 2);
    CHECK(curve_segment_count(2, CurveBasis::bspline, 2) == 0);
    CHECK_THROWS_AS(append_curve(set, std::span(p).first(3), std::span(r).first(3), CurveBasis::bezier, 3), std::invalid_argument);
  }
}

TEST_CASE("curve: a degenerate curve (one point, or zero width) is left out and hits nothing") {
  CurveSet set;
  const std::vector<Vec3> same(4, Vec3{1, 1, 1});
  const std::vector<float> zero(4, 0.0f), some(4, 0.1f);
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  CHECK(append_curve(set, same, some, CurveBasis::bezier, 3) == 1);
  CHECK(append_curve(set, line, zero, CurveBasis::bezier, 3) == 1);
  CHECK(set.segments() == 0);
  // A segment whose tangent vanishes at an end (p0 = p1) still gives a finite, non-zero ∂p/∂u there.
  CurveSet kinked;
  const std::vector<Vec3> stalled = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  append_curve(kinked, stalled, some, CurveBasis::bezier, 3);
  SurfaceHit hit;
  curve_surface(kinked, 0, 0.0f, {0, 0.05f, 1}, {0, 0, -1}, 1.0f, {0, 0, 0}, hit);
  CHECK(length(hit.dpdu) > 0.0f);
  CHECK(is_finite(hit.dpdu));
  CHECK(is_finite(hit.geometric_normal));
  CHECK(std::isfinite(hit.uv.y));
}

TEST_CASE("curve: a ribbon turns from one end's normal to the other's along the arc, as pbrt-v4's slerp") {
  // One straight segment along x (u = x/2 + 1/2), normal +z at u = 0 and +y at u = 1: a quarter turn about the
  // fibre. pbrt-v4's normal at u is slerp = (0, sin(πu/2), cos(πu/2)); a straight blend of the two normals would be
  // up to 4.1° away from it (at u ≈ 0.25 and 0.75), the cubic Embree turns the ribbon by at most 0.08°.
  CurveSet set;
  set.kind = CurveKind::ribbon;
  const std::vector<Vec3> points = {{-1, 0, 0}, {-1.0f / 3, 0, 0}, {1.0f / 3, 0, 0}, {1, 0, 0}};
  const std::vector<float> radii(4, 0.05f);
  const std::vector<Vec3> normals = {{0, 0, 1}, {0, 1, 0}};
  append_curve(set, points, radii, CurveBasis::bezier, 3, normals);
  EmbreeScene scene;
  scene.add_curves(std::move(set), 0);
  scene.commit();
  constexpr double kHalfPi = 1.5707963267948966;
  for (const float u : {0.1f, 0.25f, 0.4f, 0.5f, 0.6f, 0.75f, 0.9f}) {
    CAPTURE(u);
    const Vec3 n{0.0f, float(std::sin(kHalfPi * u)), float(std::cos(kHalfPi * u))};
    const Vec3 centre{2.0f * u - 1.0f, 0.0f, 0.0f};
    const auto hit = scene.intersect(ray_from(centre + n, -n));  // face-on at the centreline
    REQUIRE(hit);
    CHECK(hit->uv.x == doctest::Approx(u).epsilon(1e-3));
    const double degrees = std::acos(std::min(1.0f, std::fabs(dot(hit->geometric_normal, n)))) / kHalfPi * 90.0;
    CHECK(degrees < 0.15);
    CHECK(dot(hit->shading_normal, n) > 0.0f);  // on the side the ribbon's normals give
  }
  // The slerp itself: the ends, the middle, and a half turn (about some perpendicular, still a unit vector).
  CHECK(length(slerp_unit({0, 0, 1}, {0, 1, 0}, 0.5f) - normalize(Vec3{0, 1, 1})) < 1e-6f);
  CHECK(length(slerp_unit({0, 0, 1}, {0, 1, 0}, 0.0f) - Vec3{0, 0, 1}) < 1e-6f);
  CHECK(length(slerp_unit({0, 0, 1}, {0, 1, 0}, 1.0f) - Vec3{0, 1, 0}) < 1e-6f);
  const Vec3 half = slerp_unit({0, 0, 1}, {0, 0, -1}, 0.5f);
  CHECK(length(half) == doctest::Approx(1.0f));
  CHECK(std::fabs(half.z) < 1e-6f);
}
