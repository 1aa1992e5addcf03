// ∂p/∂u and ∂p/∂v at hits (SurfaceHit::dpdu/dpdv, MaterialContext): the tangents normal and bump maps need,
// checked against the parametrisation they differentiate.
#include <doctest/doctest.h>

#include <cmath>

#include "render/scene/embree_scene.h"
#include "transport/geometry/transform.h"

using namespace rimu;

namespace {

Ray ray_to(Vec3 from, Vec3 to) {
  Ray r;
  r.origin = from;
  r.direction = normalize(to - from);
  r.t_min = 0.0f;
  r.t_max = 1e30f;
  return r;
}

// A triangle whose uvs are a sheared, scaled copy of its positions' plane, so ∂p/∂u ≠ b − a.
TriangleMesh sheared_triangle(bool with_uvs) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  if (with_uvs) m.uvs = {{0.1f, 0.2f}, {0.5f, 0.3f}, {0.2f, 0.9f}};
  m.indices = {0, 1, 2};
  return m;
}

void check_close(Vec3 a, Vec3 b, float tolerance) {
  CHECK(a.x == doctest::Approx(b.x).epsilon(tolerance));
  CHECK(a.y == doctest::Approx(b.y).epsilon(tolerance));
  CHECK(a.z == doctest::Approx(b.z).epsilon(tolerance));
}

// p is affine in uv over a triangle: each edge must equal Δu·∂p/∂u + Δv·∂p/∂v exactly (to rounding).
void check_edges(const TriangleMesh& m, const SurfaceHit& hit, const Transform& to_world) {
  for (int e = 1; e < 3; ++e) {
    const Vec3 edge = to_world.vector(m.positions[size_t(e)] - m.positions[0]);
    const Vec2 duv{m.uvs[size_t(e)].x - m.uvs[0].x, m.uvs[size_t(e)].y - m.uvs[0].y};
    check_close(hit.dpdu * duv.x + hit.dpdv * duv.y, edge, 1e-5f);
  }
}

}  // namespace

TEST_CASE("surface tangents: a triangle's dp/du, dp/dv reproduce its edges from its uvs") {
  SUBCASE("with uvs") {
    EmbreeScene scene;
    scene.add_mesh(sheared_triangle(true), 0, -1);
    scene.commit();
    const auto hit = scene.intersect(ray_to({0.5f, 0.5f, 1.0f}, {0.5f, 0.5f, 0.0f}));
    REQUIRE(hit);
    check_edges(sheared_triangle(true), *hit, Transform());
    CHECK(dot(hit->dpdu, hit->geometric_normal) == doctest::Approx(0.0f).epsilon(1e-6f));
  }
  SUBCASE("without uvs the barycentrics are the uvs: dp/du = b − a, dp/dv = c − a") {
    EmbreeScene scene;
    scene.add_mesh(sheared_triangle(false), 0, -1);
    scene.commit();
    const auto hit = scene.intersect(ray_to({0.5f, 0.5f, 1.0f}, {0.5f, 0.5f, 0.0f}));
    REQUIRE(hit);
    check_close(hit->dpdu, {2, 0, 0}, 1e-6f);
    check_close(hit->dpdv, {0, 3, 0}, 1e-6f);
  }
  SUBCASE("through an instance's transform") {
    EmbreeScene scene;
    std::vector<std::pair<TriangleMesh, int>> meshes;
    meshes.emplace_back(sheared_triangle(true), 0);
    const int prototype = scene.add_prototype(std::move(meshes));
    const Transform to_world = Transform::translate({5, 0, 0}) * Transform::rotate(30.0f, {0, 0, 1}) * Transform::scale({2, 1, 1});
    scene.add_instance(prototype, to_world);
    scene.commit();
    const Vec3 target = to_world.point({0.5f, 0.5f, 0.0f});
    const auto hit = scene.intersect(ray_to(target + Vec3{0, 0, 1}, target));
    REQUIRE(hit);
    check_edges(sheared_triangle(true), *hit, to_world);
  }
  SUBCASE("coincident uvs give zero tangents (unknown), not NaN") {
    TriangleMesh m = sheared_triangle(true);
    m.uvs = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}};
    EmbreeScene scene;
    scene.add_mesh(m, 0, -1);
    scene.commit();
    const auto hit = scene.intersect(ray_to({0.5f, 0.5f, 1.0f}, {0.5f, 0.5f, 0.0f}));
    REQUIRE(hit);
    CHECK(length(hit->dpdu) == 0.0f);
    CHECK(length(hit->dpdv) == 0.0f);
  }
}

TEST_CASE("surface tangents: pbrt-v4's default uv (0,0), (1,0), (1,1) without uvs, and after a mirroring transform") {
  // A point with barycentrics (b0, b1, b2) has pbrt's uv b1·(1,0) + b2·(1,1) = (b1 + b2, b2) in the order pbrt read
  // the vertices; the tangents are then ∂p/∂u = v1 − v0, ∂p/∂v = v2 − v1 (the edges in uv: (1,0) and (0,1)).
  const Vec3 v0{0, 0, 0}, v1{2, 0, 0}, v2{0.5f, 3, 0};
  const float b1 = 0.3f, b2 = 0.25f;
  for (const bool mirrored : {false, true}) {
    CAPTURE(mirrored);
    TriangleMesh m = sheared_triangle(false);
    m.positions = {v0, v1, v2};
    m.default_uvs = TriangleMesh::DefaultUvs::pbrt;
    // A mirror (x → −x) rewinds the triangle (vertices 1 and 2 swap); the uvs stay with their vertices.
    const Transform to_world = mirrored ? Transform::scale({-1, 1, 1}) : Transform();
    m.transform(to_world);
    EmbreeScene scene;
    scene.add_mesh(m, 0, -1);
    scene.commit();
    const Vec3 target = to_world.point(v0 * (1 - b1 - b2) + v1 * b1 + v2 * b2);
    const auto hit = scene.intersect(ray_to(target + Vec3{0, 0, 1}, target));
    REQUIRE(hit);
    CHECK(hit->uv.x == doctest::Approx(b1 + b2).epsilon(1e-5));
    CHECK(hit->uv.y == doctest::Approx(b2).epsilon(1e-5));
    check_close(hit->dpdu, to_world.vector(v1 - v0), 1e-5f);
    check_close(hit->dpdv, to_world.vector(v2 - v1), 1e-5f);
  }
}

TEST_CASE("surface tangents: a sphere's dp/du, dp/dv match finite differences of its parametrisation") {
  EmbreeScene scene;
  const Vec3 centre{1, 2, 3};
  const float radius = 1.5f;
  scene.add_sphere(centre, radius, 0);
  scene.commit();
  // Points at several polar and azimuthal angles (away from the poles and from the u seam at φ = ±π).
  for (const float theta : {0.4f, 1.2f, 2.5f})
    for (const float phi : {-2.0f, 0.3f, 1.7f}) {
      const auto point_at = [&](float t, float p) {
        return centre + Vec3{std::sin(t) * std::cos(p), std::cos(t), std::sin(t) * std::sin(p)} * radius;
      };
      const Vec3 p = point_at(theta, phi);
      const auto hit = scene.intersect(ray_to(centre + (p - centre) * 3.0f, p));
      REQUIRE(hit);
      CHECK(dot(hit->dpdu, hit->geometric_normal) == doctest::Approx(0.0f).epsilon(1e-4f));
      CHECK(dot(hit->dpdv, hit->geometric_normal) == doctest::Approx(0.0f).epsilon(1e-4f));
      // u = ½ + φ/2π, v = θ/π (shade_hit's convention): central differences in φ and θ.
      const float h = 1e-3f;
      const Vec3 du = (point_at(theta, phi + h) - point_at(theta, phi - h)) * (float(2.0 * M_PI) / (2.0f * h));
      const Vec3 dv = (point_at(theta + h, phi) - point_at(theta - h, phi)) * (float(M_PI) / (2.0f * h));
      for (auto [got, want] : {std::pair{hit->dpdu, du}, std::pair{hit->dpdv, dv}}) {
        CHECK(length(got - want) <= 1e-3f * length(want));
      }
      // And the hit's uv is the parametrisation's (so the tangents belong to the uv the textures see).
      CHECK(hit->uv.x == doctest::Approx(0.5 + phi / (2.0 * M_PI)).epsilon(1e-4));
      CHECK(hit->uv.y == doctest::Approx(theta / M_PI).epsilon(1e-4));
    }
}

TEST_CASE("surface tangents: a sphere with pbrt-v4's uv (uv_axes) has pbrt's u, v and their dp/du, dp/dv") {
  // Object axes in world: a rotation about the world y-axis by 90° composed with a mirror (x → −x), as an imported
  // pbrt sphere under pbrt's camera mirror gets them. Orthonormal, left-handed.
  const std::array<Vec3, 3> axes = {Vec3{0, 0, 1}, Vec3{0, 1, 0}, Vec3{1, 0, 0}};
  EmbreeScene scene;
  const Vec3 centre{1, 2, 3};
  const float radius = 1.5f;
  scene.add_sphere(centre, radius, 0, axes);
  scene.commit();
  // pbrt's sphere: p = r·(sin θ cos φ, sin θ sin φ, cos θ) in object axes; u = φ/2π (φ in [0, 2π)), v = 1 − θ/π.
  const auto point_at = [&](float theta, float phi) {
    const Vec3 o{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    return centre + (axes[0] * o.x + axes[1] * o.y + axes[2] * o.z) * radius;
  };
  for (const float theta : {0.4f, 1.2f, 2.5f})
    for (const float phi : {0.3f, 1.7f, 4.0f, 5.9f}) {
      const Vec3 p = point_at(theta, phi);
      const auto hit = scene.intersect(ray_to(centre + (p - centre) * 3.0f, p));
      REQUIRE(hit);
      CHECK(hit->uv.x == doctest::Approx(phi / (2.0 * M_PI)).epsilon(1e-4));
      CHECK(hit->uv.y == doctest::Approx(1.0 - theta / M_PI).epsilon(1e-4));
      // ∂p/∂u = ∂p/∂φ·2π, ∂p/∂v = ∂p/∂θ·(−π): central differences.
      const float h = 1e-3f;
      const Vec3 du = (point_at(theta, phi + h) - point_at(theta, phi - h)) * (float(2.0 * M_PI) / (2.0f * h));
      const Vec3 dv = (point_at(theta + h, phi) - point_at(theta - h, phi)) * (float(-M_PI) / (2.0f * h));
      for (auto [got, want] : {std::pair{hit->dpdu, du}, std::pair{hit->dpdv, dv}}) {
        CHECK(length(got - want) <= 1e-3f * length(want));
      }
    }
  // The +z pole of the object (world +x here) is v = 1, the −z pole v = 0.
  const auto top = scene.intersect(ray_to(centre + Vec3{5, 0.01f, 0}, centre));
  REQUIRE(top);
  CHECK(top->uv.y == doctest::Approx(1.0f).epsilon(1e-2));
}
