// Ray differentials (transport/geometry/ray_differentials.h): the footprint at a hit and through a mirror or a
// refracting plane, against finite differences of the rays they stand for; and the bump map's step from it.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>

#include "transport/geometry/ray_differentials.h"
#include "transport/textures/shading_normal_map.h"

using namespace rimu;

namespace {

struct Plane {
  Vec3 point, normal;  // normal unit
};

std::optional<Vec3> hit(Vec3 origin, Vec3 direction, const Plane& plane) {
  const float denom = dot(plane.normal, direction);
  if (denom == 0.0f) return std::nullopt;
  return origin + direction * (dot(plane.normal, plane.point - origin) / denom);
}

Vec3 mirror(Vec3 d, Vec3 n) { return d - n * (2.0f * dot(d, n)); }

// Snell refraction of d (travelling towards the surface) through a plane of unit normal n facing d's origin,
// relative index eta = ηt/ηi.
Vec3 refract_through(Vec3 d, Vec3 n, float eta) {
  const float ci = -dot(d, n);
  const float st2 = (1.0f - ci * ci) / (eta * eta);
  return normalize(d / eta + n * (ci / eta - std::sqrt(1.0f - st2)));
}

// A family of camera-like rays from the origin through film point (x, y) on the z = 1 plane.
Vec3 film_direction(float x, float y) { return normalize(Vec3{x, y, 1.0f}); }

void check_close(Vec3 a, Vec3 b, float tolerance) {
  CAPTURE(a.x);
  CAPTURE(a.y);
  CAPTURE(a.z);
  CAPTURE(b.x);
  CAPTURE(b.y);
  CAPTURE(b.z);
  CHECK(length(a - b) <= tolerance);
}

}  // namespace

TEST_CASE("ray differentials: dp/dx and the uv derivatives on a sheared plane match the neighbouring rays' hits") {
  // Receiver through (0.3, −0.2, 4) with a tilted normal; u and v along sheared, scaled tangents, so that the uv
  // derivatives need the full least-squares solve, not a projection.
  const Plane receiver{{0.3f, -0.2f, 4.0f}, normalize(Vec3{0.2f, 0.4f, -1.0f})};
  const Vec3 dpdu = cross(receiver.normal, Vec3{0, 1, 0}) * 2.0f;
  const Vec3 dpdv = normalize(cross(receiver.normal, dpdu)) * 0.7f + dpdu * 0.3f;
  const float x0 = 0.1f, y0 = -0.05f, step = 1e-3f;
  const Vec3 p = *hit({}, film_direction(x0, y0), receiver);
  const Vec3 px = *hit({}, film_direction(x0 + step, y0), receiver), py = *hit({}, film_direction(x0, y0 + step), receiver);
  const RayDifferentials rays{{}, film_direction(x0 + step, y0), {}, film_direction(x0, y0 + step)};
  const SurfaceDifferentials d = surface_differentials(p, receiver.normal, dpdu, dpdv, rays);
  check_close(d.dpdx, px - p, 1e-6f);
  check_close(d.dpdy, py - p, 1e-6f);
  // The uv of a point q of the plane: solve q − p = u·dpdu + v·dpdv (exactly, in double, by Cramer on two axes
  // chosen from the normal) — what the neighbouring rays' uvs differ by.
  const auto uv_of = [&](Vec3 q) {
    const Vec3 e = q - p;
    const double a = double(dot(dpdu, dpdu)), b = double(dot(dpdu, dpdv)), c = double(dot(dpdv, dpdv));
    const double r0 = double(dot(dpdu, e)), r1 = double(dot(dpdv, e));
    const double det = a * c - b * b;
    return Vec2{float((c * r0 - b * r1) / det), float((a * r1 - b * r0) / det)};
  };
  const Vec2 ux = uv_of(px), uy = uv_of(py);
  CHECK(d.duvdx.x == doctest::Approx(ux.x).epsilon(1e-4));
  CHECK(d.duvdx.y == doctest::Approx(ux.y).epsilon(1e-4));
  CHECK(d.duvdy.x == doctest::Approx(uy.x).epsilon(1e-4));
  CHECK(d.duvdy.y == doctest::Approx(uy.y).epsilon(1e-4));
  // An auxiliary ray parallel to the plane: no footprint.
  const RayDifferentials parallel{{}, normalize(cross(receiver.normal, Vec3{1, 0, 0})), {}, film_direction(x0, y0 + step)};
  const SurfaceDifferentials none = surface_differentials(p, receiver.normal, dpdu, dpdv, parallel);
  CHECK(none.dpdx == Vec3{});
  CHECK(none.duvdx.x == 0.0f);
}

TEST_CASE("ray differentials after a mirror and a refracting plane match finite differences of the bent rays") {
  const Plane mirror_plane{{0.0f, 0.0f, 5.0f}, normalize(Vec3{0.1f, 0.3f, -1.0f})};
  const float x0 = 0.12f, y0 = -0.07f, step = 1e-3f;
  for (const bool transmitted : {false, true}) {
    CAPTURE(transmitted);
    const float eta = 1.5f;
    const auto bend = [&](Vec3 d) { return transmitted ? refract_through(d, mirror_plane.normal, eta) : mirror(d, mirror_plane.normal); };
    // The main ray and the two neighbours, each bent at its own hit on the plane (flat, so exactly).
    const Vec3 d0 = film_direction(x0, y0), dx = film_direction(x0 + step, y0), dy = film_direction(x0, y0 + step);
    const Vec3 p = *hit({}, d0, mirror_plane), px = *hit({}, dx, mirror_plane), py = *hit({}, dy, mirror_plane);
    const Vec3 out = bend(d0);
    // A receiver 3 units along the bent main ray, facing it obliquely.
    const Plane receiver{p + out * 3.0f, normalize(-out + Vec3{0.2f, 0.0f, 0.1f})};
    const Vec3 q = *hit(p, out, receiver);
    const Vec3 qx = *hit(px, bend(dx), receiver), qy = *hit(py, bend(dy), receiver);

    const RayDifferentials camera{{}, dx, {}, dy};
    const SurfaceDifferentials at_mirror =
        surface_differentials(p, mirror_plane.normal, Vec3{1, 0, 0}, Vec3{0, 1, 0}, camera);
    // The relative index as the integrator recovers it from the main ray's sines.
    const float cos_i = std::fabs(dot(d0, mirror_plane.normal)), cos_t = std::fabs(dot(out, mirror_plane.normal));
    const float recovered_eta = std::sqrt(1.0f - cos_i * cos_i) / std::sqrt(1.0f - cos_t * cos_t);
    if (transmitted) CHECK(recovered_eta == doctest::Approx(eta).epsilon(1e-3));
    const std::optional<RayDifferentials> bent =
        specular_differentials(camera, p, mirror_plane.normal, at_mirror, transmitted, transmitted ? recovered_eta : 1.0f);
    REQUIRE(bent);
    const SurfaceDifferentials at_receiver =
        surface_differentials(q, receiver.normal, Vec3{1, 0, 0}, Vec3{0, 1, 0}, *bent);
    // Float rounding of points ~5 units away and of the recovered eta: 1e-5 of the 5e-3 footprint is ample.
    check_close(at_receiver.dpdx, qx - q, 2e-5f);
    check_close(at_receiver.dpdy, qy - q, 2e-5f);
  }
}

TEST_CASE("ray differentials: an auxiliary ray totally reflected where the main one refracts loses the footprint") {
  // Leaving glass (η = 1/1.5) just below the critical angle; the neighbour tilts past it.
  const Vec3 n{0, 0, 1};
  const float critical = std::asin(1.0f / 1.5f);
  const float a0 = critical - 0.001f, a1 = critical + 0.01f;
  const Vec3 d0{std::sin(a0), 0.0f, std::cos(a0)}, d1{std::sin(a1), 0.0f, std::cos(a1)};
  const RayDifferentials camera{{}, d1, {}, d0};
  const SurfaceDifferentials d{{0.01f, 0, 0}, {0, 0.01f, 0}, {}, {}};
  CHECK_FALSE(specular_differentials(camera, {}, n, d, true, 1.0f / 1.5f));
  CHECK(specular_differentials(camera, {}, n, d, false, 1.0f));
}

TEST_CASE("bump steps: half the footprint along each texture axis (pbrt-v4's rule), 0.0005 without one") {
  MaterialContext c;
  CHECK(bump_steps_uv(c).x == kBumpStepUv);
  CHECK(bump_steps_uv(c).y == kBumpStepUv);
  c.duvdx = {0.02f, -0.001f};
  c.duvdy = {-0.01f, 0.003f};
  CHECK(bump_steps_uv(c).x == doctest::Approx(0.015));
  CHECK(bump_steps_uv(c).y == doctest::Approx(0.002));
}

namespace {

// d(u, v) = amplitude·sin(2π u / period): its finite-difference slope over a step h is known in closed form.
class SineTexture final : public FloatTexture {
 public:
  SineTexture(float amplitude, float period) : a_(amplitude), period_(period) {}
  float evaluate(const MaterialContext& c) const override { return a_ * std::sin(6.2831853f * c.uv.x / period_); }

 private:
  float a_, period_;
};

class RampTexture final : public FloatTexture {
 public:
  explicit RampTexture(float slope) : slope_(slope) {}
  float evaluate(const MaterialContext& c) const override { return slope_ * c.uv.x; }

 private:
  float slope_;
};

MaterialContext flat_context() {
  MaterialContext c;
  c.uv = {0.3f, 0.6f};
  c.geometric_normal = c.shading_normal = {0, 0, 1};
  c.dpdu = {1, 0, 0};
  c.dpdv = {0, 1, 0};
  c.wo = {0, 0, 1};
  return c;
}

}  // namespace

TEST_CASE("bump with differentials: a ramp gives its analytic tilt at any footprint, a sine is differenced over it") {
  MaterialContext c = flat_context();
  const float slope = std::tan(0.35f);
  for (const float footprint : {0.0f, 1e-3f, 0.05f, 0.4f}) {
    CAPTURE(footprint);
    c.duvdx = {footprint, 0.0f};
    c.duvdy = {0.0f, footprint};
    const Vec3 n = bump_normal(c, RampTexture(slope));
    // d = k·u on a unit-speed plane: n ∝ (−k, 0, 1), tilted by atan(k) against the rise.
    CHECK(n.x == doctest::Approx(-std::sin(0.35f)).epsilon(1e-4));
    CHECK(n.z == doctest::Approx(std::cos(0.35f)).epsilon(1e-4));
  }
  // A sine of period 0.1: differenced over Δu = ½(|∂u/∂x| + |∂u/∂y|) the slope is (d(u + Δu) − d(u))/Δu, which
  // tends to zero as Δu reaches the period (the bumps average out of a footprint that wide) — the fixed step would
  // give the full local slope everywhere.
  const SineTexture sine(0.01f, 0.1f);
  for (const float footprint : {0.004f, 0.05f, 0.1f}) {
    CAPTURE(footprint);
    c.duvdx = {footprint, 0.0f};
    c.duvdy = {footprint, 0.0f};
    const float du = footprint;  // ½(|f| + |f|)
    MaterialContext shifted = c;
    shifted.uv.x += du;
    const float expected_slope = (sine.evaluate(shifted) - sine.evaluate(c)) / du;
    const Vec3 n = bump_normal(c, sine);
    CHECK(-n.x / n.z == doctest::Approx(expected_slope).epsilon(1e-3).scale(1e-4));
  }
}
