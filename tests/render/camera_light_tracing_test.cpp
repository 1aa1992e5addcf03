// What light tracing and bidirectional path tracing ask of the camera (transport/integrators/light_tracing_camera.h):
// see() inverts generate_ray (a point on a camera ray lands on that ray's film point, through a pinhole and through
// any point of a thin lens when the point is in focus), its importance is the direction density over d², and the
// direction density 1/(a cos³θ) is one over the solid angle a pixel covers, off the axis too.
#include <doctest/doctest.h>

#include <cmath>

#include "render/camera/camera.h"
#include "transport/sampling/sampler.h"

using namespace rimu;

namespace {

Camera test_camera(float lens_radius) {
  CameraSettings settings;
  settings.camera_to_world = Transform::look_at({0.3f, 1.2f, -2.0f}, {0.0f, 0.4f, 0.5f}, {0, 1, 0});
  settings.vertical_fov_deg = 50.0f;
  settings.lens_radius = lens_radius;
  settings.focus_distance = 2.5f;
  return Camera(settings, 64, 48);
}

}  // namespace

TEST_CASE("light tracing camera: see() inverts generate_ray, importance = direction density / d²") {
  IndependentSampler sampler(5);
  for (const float lens_radius : {0.0f, 0.05f}) {
    CAPTURE(lens_radius);
    const Camera camera = test_camera(lens_radius);
    REQUIRE(camera.supports_light_tracing());
    for (int i = 0; i < 200; ++i) {
      sampler.start_pixel_sample(i, 0, 0);
      const Vec2 film{sampler.next_1d() * 64.0f, sampler.next_1d() * 48.0f};
      const Vec2 lens = sampler.next_2d();
      const Ray ray = camera.generate_ray(film.x, film.y, lens);
      // A point on the ray: anywhere for a pinhole, on the plane in focus for a thin lens (its image is sharp).
      const Vec3 axis = camera.settings().camera_to_world.vector({0, 0, 1});
      const float d = lens_radius > 0.0f ? 2.5f / dot(ray.direction, axis) : 0.5f + 4.0f * sampler.next_1d();
      const Vec3 point = ray.origin + ray.direction * d;
      const auto seen = camera.see(point, 0.0f, sampler.next_2d());
      REQUIRE(seen);
      CHECK(seen->film_px.x == doctest::Approx(film.x).epsilon(1e-3));
      CHECK(seen->film_px.y == doctest::Approx(film.y).epsilon(1e-3));
      if (lens_radius == 0.0f) {
        CHECK(seen->importance * d * d == doctest::Approx(camera.direction_density(ray.direction, 0.0f)).epsilon(1e-4));
      }
    }
  }
}

TEST_CASE("light tracing camera: the direction density is one over a pixel's solid angle") {
  const Camera camera = test_camera(0.0f);
  for (const Vec2 pixel : {Vec2{32, 24}, Vec2{2, 3}, Vec2{60, 45}, Vec2{10, 40}}) {
    CAPTURE(pixel.x);
    CAPTURE(pixel.y);
    // The pixel's solid angle from its corners' directions: two spherical triangles, each by Van Oosterom and
    // Strackee's formula tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a).
    const Vec3 a = camera.generate_ray(pixel.x, pixel.y, {0.5f, 0.5f}).direction;
    const Vec3 b = camera.generate_ray(pixel.x + 1, pixel.y, {0.5f, 0.5f}).direction;
    const Vec3 c = camera.generate_ray(pixel.x + 1, pixel.y + 1, {0.5f, 0.5f}).direction;
    const Vec3 e = camera.generate_ray(pixel.x, pixel.y + 1, {0.5f, 0.5f}).direction;
    const auto triangle = [](Vec3 p, Vec3 q, Vec3 r) {
      return 2.0 * std::atan2(std::fabs(double(dot(p, cross(q, r)))),
                              1.0 + double(dot(p, q)) + double(dot(q, r)) + double(dot(r, p)));
    };
    const double solid_angle = triangle(a, b, c) + triangle(a, c, e);
    const Vec3 centre = camera.generate_ray(pixel.x + 0.5f, pixel.y + 0.5f, {0.5f, 0.5f}).direction;
    CHECK(double(camera.direction_density(centre, 0.0f)) * solid_angle == doctest::Approx(1.0).epsilon(2e-3));
  }
  CHECK(camera.direction_density(-camera.settings().camera_to_world.vector({0, 0, 1}), 0.0f) == 0.0f);
}
