// A projector (a slide projector, a gobo or a cookie in front of a lamp; pbrt-v4's `LightSource "projection"`): a
// point light whose intensity towards each direction is an image's pixel, seen through a pinhole.
//
// Geometry, in the light's frame (s: image right, t: image up, n: the projection axis): a direction w with w·n > 0
// meets the image plane at distance 1 at (w·s, w·t)/(w·n); divided by tan(fov/2) that is the screen point. The
// screen spans [−1, 1] along the image's SHORTER side and ±aspect along the longer (pbrt-v4's screen window), so
// `fov` is the full angle across the shorter side. Outside the screen, and behind the projector, it emits nothing.
// The pixel is the nearest one (pbrt-v4's LookupNearest: a projector's pixels stay crisp), row 0 at the top (t up).
//
// Intensity: I(λ, w) = scale · pixel(λ) in W/(sr·nm), constant over a pixel's directions: as in pbrt-v4, there is
// no cos³ falloff in I itself; a plane square to the axis still receives E = I cos θ / d², which falls off as cos³ θ
// towards the edges of the picture because d grows.
#pragma once

#include <memory>

#include "transport/geometry/frame.h"
#include "transport/lights/light.h"
#include "transport/lights/radiance_image.h"

namespace rimu {

class ProjectionLight final : public Light {
 public:
  /// `frame`: s (image right), t (image up), n (the axis), orthonormal in world space (either handedness: a mirrored
  /// frame shows the picture mirrored). `fov_deg` in (0, 180). `image` pixels times `scale` are the intensity
  /// spectra in W/(sr·nm) (scale finite, ≥ 0).
  ProjectionLight(Vec3 position_m, Frame frame, double fov_deg, std::shared_ptr<const RadianceImage> image,
                  double scale);

  /// The direction to the projector with I(−wi)/d², pdf 1, is_delta; std::nullopt at the light, outside the picture
  /// or where its pixel is black.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  float pdf_li(const LightReference&, Vec3, const SurfaceHit*) const override { return 0.0f; }
  /// Φ = Σ_pixels ∫I dλ · Ω_pixel, Ω_pixel = ∫ cos³θ dA over the pixel's patch of the image plane at distance 1
  /// (in closed form).
  double total_power_w(double scene_radius_m) const override;
  bool is_delta() const override { return true; }
  std::optional<Vec3> emission_centre_m(int) const override { return position_m_; }
  /// The brightest pixel's ∫I dλ in the cone about the axis that holds the picture's corners (no falloff beyond).
  std::optional<LightBounds> part_bounds(int part) const override;

  /// The pixel (column, row from the top) lit towards world direction `w_out` (unit, away from the light), or
  /// {−1, −1} outside the picture or behind the projector.
  std::pair<int, int> pixel_towards(Vec3 w_out) const;
  /// Half the angle across the picture's diagonal, radians.
  double corner_angle_rad() const;
  /// Σ_pixels luminance(pixel) · Ω_pixel: the luminous flux per unit of luminance the image gives (lm per cd of a
  /// white pixel, when the pixels are scaled so that a pixel of luminance 1 is 1 cd).
  double luminance_weighted_solid_angle_sr() const { return luminance_solid_angle_sr_; }

 private:
  Vec3 position_m_;
  Frame frame_;
  std::shared_ptr<const RadianceImage> image_;
  float scale_;
  float tan_half_fov_;
  float half_width_, half_height_;  // the screen window: ±half_width × ±half_height (one of them is 1)
  double brightest_integral_ = 0.0;  // max over pixels of scale·∫pixel dλ
  double power_w_ = 0.0;
  double luminance_solid_angle_sr_ = 0.0;
};

}  // namespace rimu
