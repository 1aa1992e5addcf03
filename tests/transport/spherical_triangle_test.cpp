// Directions uniform in a triangle's solid angle (transport/sampling/spherical_triangle.h): the solid angle against closed
// forms, every sample inside the triangle, and the samples' mean direction against the exact first moment
// ∫ ω dω = ½ Σᵢ Θᵢ Γᵢ over the triangle's edges (Θᵢ the angle edge i subtends, Γᵢ the unit normal of the plane
// through the point and that edge, pointing into the triangle's cone; Arvo 1995, "Applications of irradiance
// tensors"), which a sampler with the wrong density would miss.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "light_test_support.h"
#include "statistics.h"
#include "transport/sampling/spherical_triangle.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;

// ½ Σ Θᵢ Γᵢ for the triangle seen from p, with Γᵢ oriented towards the triangle's interior.
Vec3 first_moment(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2) {
  const Vec3 corner[3] = {normalize(v0 - p), normalize(v1 - p), normalize(v2 - p)};
  const Vec3 inside = normalize(corner[0] + corner[1] + corner[2]);
  double m[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const Vec3 a = corner[i], b = corner[(i + 1) % 3];
    const double theta = std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0));
    Vec3 gamma = normalize(cross(a, b));
    if (dot(gamma, inside) < 0.0f) gamma = -gamma;
    m[0] += 0.5 * theta * gamma.x;
    m[1] += 0.5 * theta * gamma.y;
    m[2] += 0.5 * theta * gamma.z;
  }
  return {float(m[0]), float(m[1]), float(m[2])};
}

}  // namespace

TEST_CASE("spherical triangle: the solid angle of an octant and of a far triangle") {
  // The octant's triangle (1,0,0), (0,1,0), (0,0,1) from the origin: one eighth of the sphere, π/2.
  CHECK(spherical_triangle_solid_angle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}) == doctest::Approx(kPi / 2).epsilon(1e-6));
  // A small triangle of area A facing the point at distance d: A/d² to second order.
  const double a = 1e-3, d = 2.0;
  CHECK(spherical_triangle_solid_angle({0, 0, 0}, {0, 0, float(d)}, {float(a), 0, float(d)}, {0, float(2 * a), float(d)}) ==
        doctest::Approx(a * a / (d * d)).epsilon(1e-4));
  // The point in the triangle's plane: 0.
  CHECK(spherical_triangle_solid_angle({5, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}) == 0.0);
  CHECK_FALSE(sample_spherical_triangle({5, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3f, 0.6f}).has_value());
}

TEST_CASE("spherical triangle: samples lie in the triangle and their mean direction is the exact first moment") {
  struct Case {
    Vec3 p, v0, v1, v2;
  };
  const Case cases[] = {
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},                  // the octant (Ω = π/2)
      {{0.1f, 0.2f, 0.01f}, {-1, -1, 0}, {2, -1, 0}, {0, 3, 0}},      // a large triangle from 1 cm: Ω near 2π
      {{0.3f, 0.1f, 0.5f}, {0, 0, 0}, {1, 0, 0.2f}, {0.05f, 0.02f, 1}},  // a thin sliver seen obliquely
  };
  std::mt19937 rng(7);
  for (const Case& c : cases) {
    const double omega = spherical_triangle_solid_angle(c.p, c.v0, c.v1, c.v2);
    REQUIRE(omega > 0.0);
    const Vec3 exact = first_moment(c.p, c.v0, c.v1, c.v2);
    test::MeanEstimate x, y, z;
    const Vec3 normal = normalize(cross(c.v1 - c.v0, c.v2 - c.v0));
    int outside = 0, not_unit = 0;
    for (int i = 0; i < 100000; ++i) {
      const auto w = sample_spherical_triangle(c.p, c.v0, c.v1, c.v2, {test::uniform01(rng), test::uniform01(rng)});
      if (!w) {
        ++not_unit;
        continue;
      }
      if (!(std::abs(length(*w) - 1.0f) < 1e-5f)) ++not_unit;
      // Where the direction meets the triangle's plane: barycentrics ≥ 0 (to rounding).
      const Vec3 q = c.p + *w * (dot(normal, c.v0 - c.p) / dot(normal, *w));
      const float area2 = dot(cross(c.v1 - c.v0, c.v2 - c.v0), normal);
      const float b1 = dot(cross(q - c.v0, c.v2 - c.v0), normal) / area2;
      const float b2 = dot(cross(c.v1 - c.v0, q - c.v0), normal) / area2;
      if (b1 < -1e-4f || b2 < -1e-4f || b1 + b2 > 1.0f + 1e-4f) ++outside;
      x.add(w->x * omega);
      y.add(w->y * omega);
      z.add(w->z * omega);
    }
    CHECK(outside == 0);
    CHECK(not_unit == 0);
    CAPTURE(omega);
    CHECK(std::abs(x.mean() - exact.x) <= 4.5 * x.standard_error());
    CHECK(std::abs(y.mean() - exact.y) <= 4.5 * y.standard_error());
    CHECK(std::abs(z.mean() - exact.z) <= 4.5 * z.standard_error());
  }
}

TEST_CASE("spherical triangle: Van Oosterom-Strackee's solid angle equals Girard's excess, and sampling reports it") {
  // Ω is computed as 2 atan2(|a·(b×c)|, 1 + a·b + b·c + c·a); Girard's α + β + γ − π (each corner angle between
  // the tangents of its two arcs, in long double here) is an independent closed form of the same quantity. Random
  // triangles from near (Ω up to ~2π) to far (Ω ~ 1e-6) and thin ones; the sampler must report the same Ω.
  const auto girard = [](Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2) {
    using L = long double;
    struct V {
      L x, y, z;
    };
    const auto unit = [&](Vec3 v) {
      const V d{L(v.x) - p.x, L(v.y) - p.y, L(v.z) - p.z};
      const L l = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
      return V{d.x / l, d.y / l, d.z / l};
    };
    const auto dotl = [](V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
    const auto angle = [&](V a, V b, V c) {
      const V tb{b.x - a.x * dotl(a, b), b.y - a.y * dotl(a, b), b.z - a.z * dotl(a, b)};
      const V tc{c.x - a.x * dotl(a, c), c.y - a.y * dotl(a, c), c.z - a.z * dotl(a, c)};
      const V x{tb.y * tc.z - tb.z * tc.y, tb.z * tc.x - tb.x * tc.z, tb.x * tc.y - tb.y * tc.x};
      return std::atan2(std::sqrt(dotl(x, x)), dotl(tb, tc));
    };
    const V a = unit(v0), b = unit(v1), c = unit(v2);
    return double(angle(a, b, c) + angle(b, c, a) + angle(c, a, b) - std::numbers::pi_v<long double>);
  };
  std::mt19937 rng(29);
  int checked = 0;
  for (int k = 0; k < 3000; ++k) {
    const float scale = std::pow(10.0f, -3.0f + 4.0f * test::uniform01(rng));  // triangle size / distance
    const auto point = [&] {
      return Vec3{scale * (test::uniform01(rng) - 0.5f), scale * (test::uniform01(rng) - 0.5f),
                  1.0f + scale * (test::uniform01(rng) - 0.5f)};
    };
    const Vec3 p{0, 0, 0}, v0 = point(), v1 = point(), v2 = k % 3 == 0 ? v0 + (v1 - v0) * 0.5f + Vec3{0, 1e-4f * scale, 0}
                                                                       : point();
    const double omega = spherical_triangle_solid_angle(p, v0, v1, v2), reference = girard(p, v0, v1, v2);
    CAPTURE(scale);
    CAPTURE(reference);
    // Both in double-or-better from the same float corners: agreement to ~1e-9 relative, or 1e-15 sr absolute.
    CHECK(std::fabs(omega - reference) <= 1e-9 * reference + 1e-15);
    double reported = -1.0;
    const auto w = sample_spherical_triangle(p, v0, v1, v2, {test::uniform01(rng), test::uniform01(rng)}, &reported);
    CHECK(reported == omega);
    if (omega > 1e-9) CHECK(w.has_value());
    if (!(omega > 0.0)) CHECK_FALSE(w.has_value());
    ++checked;
  }
  CHECK(checked == 3000);
}
