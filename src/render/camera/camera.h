// The camera: maps a point on the film and a point on the lens to a primary ray.
#pragma once

#include <optional>

#include "transport/geometry/frame.h"
#include "transport/geometry/motion_transform.h"
#include "transport/geometry/ray.h"
#include "transport/geometry/ray_differentials.h"
#include "transport/geometry/transform.h"
#include "transport/integrators/light_tracing_camera.h"

namespace rimu {

/// How a spherical camera maps the image to directions (docs/scene-format.md, camera `spherical`).
enum class SphericalMapping {
  none,             ///< not a spherical camera
  equirectangular,  ///< latitude-longitude: the image centre on the view axis, the top row straight up
  equal_area_octahedral,  ///< Clarberg's square equal-area map: the centre on the view axis, the corners behind
};

/// A pinhole (lens_radius = 0) or thin-lens perspective camera, an orthographic one (orthographic_height > 0:
/// parallel rays along +z from the points of a film orthographic_height scene units tall; with lens_radius > 0
/// they pass a thin lens focused at focus_distance, as pbrt's OrthographicCamera), or a spherical one (spherical
/// ≠ none: every pixel a direction of the whole sphere around the camera's position, pbrt's SphericalCamera).
///
/// Film coordinates are continuous pixels: (0,0) is the top-left corner of the image, (width, height) the
/// bottom-right. The vertical field of view spans the image height. The thin lens focuses at `focus_distance`
/// along the view axis (pbrt's model: the ray through the lens centre is undeviated; all rays through a film point
/// meet on the plane of focus).
struct CameraSettings {
  Transform camera_to_world;       ///< see Transform::look_at: +z forward, +y up, +x image right
  /// A moving camera's camera_to_world at shutter close (motion blur; MotionTransform interpolates); none: it stays.
  std::optional<Transform> camera_to_world_end;
  float vertical_fov_deg = 40.0f;
  float lens_radius = 0.0f;        ///< aperture radius in scene units; 0 = pinhole
  float focus_distance = 1.0f;     ///< scene units, along +z
  float orthographic_height = 0.0f;  ///< > 0: orthographic, the film's height in scene units (fov unused)
  SphericalMapping spherical = SphericalMapping::none;  ///< ≠ none: spherical (fov, lens and height unused)
  /// A spherical camera's mapping turned in camera space: the camera-space directions of the mapping's own x
  /// (right), y (up) and z (forward) axes; either handedness. The pbrt importer uses it to follow pbrt's mappings.
  Frame spherical_frame{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
};

/// The camera-space direction (x right, y up, z forward; before spherical_frame) that `mapping` gives the image
/// point (u, v) ∈ [0, 1]², u across from the left edge, v down from the top. Equirectangular: longitude
/// φ = 2π(u − ½) from the view axis, positive towards the right, and polar angle θ = πv from straight up.
/// Equal-area octahedral: Clarberg's mapping with the image's centre on +z, the middle of its right edge on +x and
/// the middle of its bottom edge on −y (down).
Vec3 spherical_camera_direction(SphericalMapping mapping, Vec2 uv);

class Camera final : public LightTracingCamera {
 public:
  Camera(const CameraSettings& settings, int image_width, int image_height);
  /// The primary ray through film point (x, y) (in pixels) and lens sample u ∈ [0,1)², at `time` in the shutter
  /// (Ray::time; a moving camera is where it is then). Direction is unit length.
  Ray generate_ray(float film_x, float film_y, Vec2 lens_u, float time = 0.0f) const;
  /// The differentials of `ray` (= generate_ray(film_x, film_y, lens_u, ray.time)): the rays through the film points
  /// one pixel right and one pixel down with the same lens sample (so a thin lens's rays still meet on the plane of
  /// focus), moved towards `ray` by `scale`. Two more generate_ray calls.
  RayDifferentials generate_differentials(const Ray& ray, float film_x, float film_y, Vec2 lens_u, float scale) const;
  const CameraSettings& settings() const { return settings_; }
  /// Whether see() can answer: a pinhole or thin-lens perspective camera (not orthographic or spherical) whose
  /// transforms are rotations and translations (a scale would change the solid angle a pixel covers).
  bool supports_light_tracing() const { return supports_light_tracing_; }
  /// Light tracing's view of the point (light_tracing_camera.h); std::nullopt behind the camera or where
  /// supports_light_tracing() is false.
  std::optional<CameraVisibility> see(Vec3 point_m, float time, Vec2 u_lens) const override;
  float direction_density(Vec3 direction, float time) const override;

 private:
  /// The camera's frame at `time`: settings_.camera_to_world, or a moving camera's interpolated one, kept in `moved`.
  const Transform& camera_to_world_at(float time, std::optional<Transform>& moved) const;
  /// The solid angle one pixel covers seen at θ off the view axis (perspective cameras): a cos³θ.
  float pixel_solid_angle(float cos_theta) const;

  CameraSettings settings_;
  std::optional<MotionTransform> motion_;  // from camera_to_world to camera_to_world_end
  float width_, height_;
  float tan_half_fov_;
  bool supports_light_tracing_ = false;  // decided once in the constructor (see supports_light_tracing)
};

/// Uniform point on the unit disc from u ∈ [0,1)² (Shirley–Chiu concentric mapping: low distortion keeps
/// stratification).
Vec2 sample_uniform_disc(Vec2 u);

}  // namespace rimu
