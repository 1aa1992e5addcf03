// A procedural cloud: density from sums of gradient noise inside a box, pbrt-v4's `cloud` medium (its CloudMedium,
// described in Pharr, Jakob & Humphreys, PBR 4th ed., §11.3), so that scenes written for pbrt render the same cloud.
#pragma once

#include <optional>

#include "transport/geometry/ray.h"
#include "transport/geometry/transform.h"
#include "transport/media/homogeneous_medium.h"

namespace rimu {

/// The density's parameters, pbrt-v4's names and defaults.
struct NoiseCloudShape {
  float density = 1.0f;    ///< scales the noise sum before the clamp to [0, 1] (pbrt's "density")
  float wispiness = 1.0f;  ///< how far the lookup point is displaced by the noise's gradient (0: not at all)
  float frequency = 5.0f;  ///< the noise's base frequency in cycles per unit of the medium's space
};

/// σ_a(x, λ) = d(x)·σ_a(λ), σ_s(x, λ) = d(x)·σ_s(λ) inside the box [bounds_min, bounds_max] of the medium's own
/// space (placed in the world by world_from_medium), 0 outside. With p in the medium's space and q = frequency·p:
///   q is displaced twice by the noise's finite-difference gradient (steps 0.05·wispiness·2⁻ⁱ at frequencies
///   10·1.99ⁱ, i = 0, 1; the gradient over 0.01),
///   n = Σ_{i<5} 2⁻⁽ⁱ⁺¹⁾ noise(1.99ⁱ q)   (Perlin 2002's improved noise, transport/textures/perlin_noise.h),
///   d = clamp(clamp((1 − p_y)·4.5·density·n, 0, 1) + 2·max(0, 0.5 − p_y), 0, 1):
/// a cloud that thins towards p_y = 1 and fills solid below p_y = 0 (above p_y = 1 the factor 1 − p_y turns
/// negative and the formula puts density where the noise sum is negative: pbrt's own boxes stop at p_y = 1). d ≤ 1,
/// so the majorant is σ_t itself over the whole box: one segment, no majorant grid (as pbrt-v4).
class NoiseCloudMedium {
 public:
  /// Throws InputError if the box is empty, a shape parameter is negative or not finite, or the transform is not
  /// invertible.
  NoiseCloudMedium(SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m, float g, NoiseCloudShape shape,
                   Vec3 bounds_min, Vec3 bounds_max, const std::optional<Transform>& world_from_medium = std::nullopt);

  /// d at a point of the medium's space (the formula above; also outside the box).
  float density_in_medium(Vec3 p) const;
  /// d at a world point, 0 outside the box.
  float density(Vec3 p_world) const;
  MediumCoefficients unit_coefficients(const SampledWavelengths& lambda) const { return unit_.coefficients(lambda); }
  /// σ_a, σ_s at a point of the medium's space inside the box.
  MediumCoefficients coefficients_in_medium(Vec3 p, const MediumCoefficients& unit) const {
    const float d = density_in_medium(p);
    return {unit.sigma_a_per_m * Float4(d), unit.sigma_s_per_m * Float4(d)};
  }
  /// The piece [t0, t1] of the ray's [t_min, t_max] inside the box, and the ray in the medium's space (same t).
  /// False if the ray misses the box.
  bool clip(const Ray& world_ray, float t_max, float& t0, float& t1, Ray& medium_ray) const;

  const HenyeyGreenstein& phase() const { return unit_.phase(); }
  const SpectrumPtr& sigma_a() const { return unit_.sigma_a(); }
  const SpectrumPtr& sigma_s() const { return unit_.sigma_s(); }
  const NoiseCloudShape& shape() const { return shape_; }

 private:
  HomogeneousMedium unit_;
  NoiseCloudShape shape_;
  Vec3 min_, max_;
  std::optional<Transform> medium_from_world_;  // empty: the medium's space is the world
};

}  // namespace rimu
