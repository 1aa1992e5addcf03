// What light tracing needs of a camera: where a point's light lands on the film and how much of it the film
// records there (the camera's importance). The camera itself lives in render/camera; the light tracer
// (caustic_light_tracer.h) sees it through this interface.
#pragma once

#include <optional>

#include "transport/geometry/vector.h"

namespace rimu {

struct CameraVisibility {
  Vec2 film_px;             ///< continuous pixel coordinates of the point's image; may lie outside the image
  Vec3 camera_position_m;   ///< the point on the lens (the pinhole) a shadow ray from the point must reach
  /// The measurement per unit of radiance leaving the point towards that lens point, in the film's units per camera
  /// sample: 1/(a cos³θ d²), with a one pixel's area on the plane at unit distance, θ the angle of the ray off the
  /// view axis and d its length (pbrt-v4's W_e/p of PerspectiveCamera::SampleWi, per pixel; the lens area cancels
  /// between the two).
  float importance = 0.0f;
};

class LightTracingCamera {
 public:
  virtual ~LightTracingCamera() = default;
  /// std::nullopt where the camera cannot see the point (behind it) or does not support light tracing. `u_lens`:
  /// a uniform point for the lens point (a pinhole ignores it).
  virtual std::optional<CameraVisibility> see(Vec3 point_m, float time, Vec2 u_lens) const = 0;
  /// The solid-angle density with which the camera draws a ray along `direction` (unit, world space, from the lens)
  /// in one camera sample of a pixel whose area the direction falls in: 1/(a cos³θ), a and θ as for `importance`
  /// (the same for a pinhole and a thin lens, whose rays through a point of the plane in focus spread over the lens
  /// alike); 0 behind the camera. The bidirectional integrator's MIS weights read it.
  virtual float direction_density(Vec3 direction, float time) const = 0;
};

}  // namespace rimu
