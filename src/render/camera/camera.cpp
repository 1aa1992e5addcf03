#include "render/camera/camera.h"

#include <cmath>

#include "transport/sampling/equal_area_square.h"

namespace rimu {

Vec2 sample_uniform_disc(Vec2 u) {
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  float r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = float(M_PI / 4.0) * (b / a);
  } else {
    r = b;
    phi = float(M_PI / 2.0) - float(M_PI / 4.0) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

Vec3 spherical_camera_direction(SphericalMapping mapping, Vec2 uv) {
  if (mapping == SphericalMapping::equal_area_octahedral) {
    // equal_area_square_to_sphere puts the image's right edge on +x and its bottom edge on +y: y is turned down.
    const Vec3 a = equal_area_square_to_sphere(uv);
    return {a.x, -a.y, a.z};
  }
  const float theta = float(M_PI) * uv.y, phi = 2.0f * float(M_PI) * (uv.x - 0.5f);
  const float sin_theta = std::sin(theta);
  return {sin_theta * std::sin(phi), std::cos(theta), sin_theta * std::cos(phi)};
}

namespace {

// Whether a transform's linear part is a rotation (orthonormal columns, within float rounding).
bool is_rigid(const Transform& t) {
  const Vec3 x = t.vector({1, 0, 0}), y = t.vector({0, 1, 0}), z = t.vector({0, 0, 1});
  const auto near = [](float a, float b) { return std::fabs(a - b) < 1e-4f; };
  return near(dot(x, x), 1) && near(dot(y, y), 1) && near(dot(z, z), 1) && near(dot(x, y), 0) && near(dot(x, z), 0) &&
         near(dot(y, z), 0);
}

}  // namespace

Camera::Camera(const CameraSettings& settings, int image_width, int image_height)
    : settings_(settings), width_(float(image_width)), height_(float(image_height)),
      tan_half_fov_(std::tan(settings.vertical_fov_deg * float(M_PI / 360.0))) {
  if (settings.camera_to_world_end) {
    // look_at frames are rotations and translations (never mirrors), so the motion is always valid.
    bool valid = false;
    motion_.emplace(settings.camera_to_world, *settings.camera_to_world_end, valid);
  }
  supports_light_tracing_ = settings.spherical == SphericalMapping::none && !(settings.orthographic_height > 0.0f) &&
                            is_rigid(settings.camera_to_world) &&
                            (!settings.camera_to_world_end || is_rigid(*settings.camera_to_world_end));
}

Ray Camera::generate_ray(float film_x, float film_y, Vec2 lens_u, float time) const {
  std::optional<Transform> moved;
  const Transform& camera_to_world = camera_to_world_at(time, moved);
  const float aspect = width_ / height_;
  if (settings_.spherical != SphericalMapping::none) {
    // Every film point a direction from the camera's position; no lens (pbrt's SphericalCamera has none either).
    const Vec3 local = spherical_camera_direction(settings_.spherical, {film_x / width_, film_y / height_});
    Ray ray;
    ray.origin = camera_to_world.point({0.0f, 0.0f, 0.0f});
    ray.direction = normalize(camera_to_world.vector(settings_.spherical_frame.to_world(local)));
    ray.time = time;
    return ray;
  }
  if (settings_.orthographic_height > 0.0f) {
    // The film point on the z = 0 plane, the ray along +z; a lens bends it through the focus point straight ahead.
    const float half = 0.5f * settings_.orthographic_height;
    Vec3 origin{(2.0f * film_x / width_ - 1.0f) * half * aspect, (1.0f - 2.0f * film_y / height_) * half, 0.0f};
    Vec3 direction{0.0f, 0.0f, 1.0f};
    if (settings_.lens_radius > 0.0f) {
      const Vec3 focus = origin + direction * settings_.focus_distance;
      const Vec2 d = sample_uniform_disc(lens_u);
      origin = origin + Vec3{settings_.lens_radius * d.x, settings_.lens_radius * d.y, 0.0f};
      direction = normalize(focus - origin);
    }
    Ray ray;
    ray.origin = camera_to_world.point(origin);
    ray.direction = normalize(camera_to_world.vector(direction));
    ray.time = time;
    return ray;
  }
  // Point on the z = 1 plane in camera space: y up, x right, image centre on the axis.
  const float sx = (2.0f * film_x / width_ - 1.0f) * tan_half_fov_ * aspect;
  const float sy = (1.0f - 2.0f * film_y / height_) * tan_half_fov_;
  Vec3 origin{0.0f, 0.0f, 0.0f};
  Vec3 direction = normalize(Vec3{sx, sy, 1.0f});
  if (settings_.lens_radius > 0.0f) {
    const Vec3 focus = direction * (settings_.focus_distance / direction.z);
    const Vec2 d = sample_uniform_disc(lens_u);
    origin = {settings_.lens_radius * d.x, settings_.lens_radius * d.y, 0.0f};
    direction = normalize(focus - origin);
  }
  Ray ray;
  ray.origin = camera_to_world.point(origin);
  ray.direction = normalize(camera_to_world.vector(direction));
  ray.time = time;
  return ray;
}

RayDifferentials Camera::generate_differentials(const Ray& ray, float film_x, float film_y, Vec2 lens_u,
                                                float scale) const {
  const Ray rx = generate_ray(film_x + 1.0f, film_y, lens_u, ray.time);
  const Ray ry = generate_ray(film_x, film_y + 1.0f, lens_u, ray.time);
  RayDifferentials d{rx.origin, rx.direction, ry.origin, ry.direction};
  d.scale_towards(ray.origin, ray.direction, scale);
  return d;
}

std::optional<CameraVisibility> Camera::see(Vec3 point_m, float time, Vec2 u_lens) const {
  if (!supports_light_tracing()) return std::nullopt;
  std::optional<Transform> moved;
  const Transform& camera_to_world = camera_to_world_at(time, moved);
  const Vec3 right = camera_to_world.vector({1, 0, 0}), up = camera_to_world.vector({0, 1, 0}),
             axis = camera_to_world.vector({0, 0, 1});
  // The point in camera space (the inverse of a rotation is its transpose: dot products with the axes).
  const Vec3 eye = camera_to_world.point({0.0f, 0.0f, 0.0f});
  const Vec3 from_eye = point_m - eye;
  const Vec3 q{dot(from_eye, right), dot(from_eye, up), dot(from_eye, axis)};
  if (!(q.z > 0.0f)) return std::nullopt;
  // The lens point o (the pinhole: the eye), uniform on the aperture as generate_ray draws it.
  Vec3 o{0.0f, 0.0f, 0.0f};
  if (settings_.lens_radius > 0.0f) {
    const Vec2 d = sample_uniform_disc(u_lens);
    o = {settings_.lens_radius * d.x, settings_.lens_radius * d.y, 0.0f};
  }
  const Vec3 to_point = q - o;
  const float distance = length(to_point);
  if (!(distance > 0.0f) || !std::isfinite(distance)) return std::nullopt;
  const float cos_theta = to_point.z / distance;
  if (!(cos_theta > 1e-6f)) return std::nullopt;
  // generate_ray's film mapping inverted: the ray o → q meets the plane in focus at p; the film point is the one
  // whose ray through the lens centre meets p, i.e. (sx, sy, 1) = p / p.z. A pinhole: the direction of q itself.
  float sx = q.x / q.z, sy = q.y / q.z;
  if (settings_.lens_radius > 0.0f) {
    const Vec3 p = o + to_point * (settings_.focus_distance / to_point.z);
    sx = p.x / settings_.focus_distance;
    sy = p.y / settings_.focus_distance;
  }
  const float aspect = width_ / height_;
  const Vec2 film{(sx / (tan_half_fov_ * aspect) + 1.0f) * 0.5f * width_, (1.0f - sy / tan_half_fov_) * 0.5f * height_};
  const float importance = 1.0f / (pixel_solid_angle(cos_theta) * distance * distance);
  if (!std::isfinite(importance) || !std::isfinite(film.x) || !std::isfinite(film.y)) return std::nullopt;
  const Vec3 lens_point = eye + right * o.x + up * o.y;
  return CameraVisibility{film, lens_point, importance};
}

float Camera::direction_density(Vec3 direction, float time) const {
  if (!supports_light_tracing()) return 0.0f;
  std::optional<Transform> moved;
  const Transform& camera_to_world = camera_to_world_at(time, moved);
  const float cos_theta = dot(direction, camera_to_world.vector({0, 0, 1}));
  if (!(cos_theta > 1e-6f)) return 0.0f;
  const float density = 1.0f / pixel_solid_angle(cos_theta);
  return std::isfinite(density) ? density : 0.0f;
}

const Transform& Camera::camera_to_world_at(float time, std::optional<Transform>& moved) const {
  // A moving camera's frame at this time (exact interpolation: a camera ray costs far more than this).
  if (motion_) moved = motion_->at(time);
  return moved ? *moved : settings_.camera_to_world;
}

float Camera::pixel_solid_angle(float cos_theta) const {
  // One pixel is 2·tan(fov/2)/height wide and high on the plane at unit distance; seen at θ off the axis its solid
  // angle is that area times cos³θ.
  const float pixel_side = 2.0f * tan_half_fov_ / height_;
  return pixel_side * pixel_side * cos_theta * cos_theta * cos_theta;
}

}  // namespace rimu
