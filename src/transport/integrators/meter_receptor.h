// The head of an illuminance meter: what fraction of the radiance arriving from each direction it counts.
// Every kind reads E = ∫ L(ω) w(ω) dω over the sphere, with its own response w.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/geometry/frame.h"
#include "transport/sampling/direction_warps.h"

namespace rimu {

/// A receptor and its response w(ω) (per steradian), with the direction density its estimator draws from.
///
/// - plane (a lux meter's cosine-corrected head facing `direction`): w = max(0, cos θ), directions cos θ/π on its side.
/// - cylinder (EN 12464-1's cylindrical illuminance: the mean vertical illuminance around a vanishingly small
///   cylinder with axis `direction`): averaging max(0, sin θ cos(φ − ψ)) over the normals ψ of the curved surface
///   gives w = sin θ / π, θ measured from the axis. A point source of intensity I at distance d: I sin θ / (π d²).
/// - semi-cylinder facing `facing` (⟂ axis; EN 13201's semi-cylindrical illuminance): averaging over the normals of
///   the half facing f gives w = sin θ (1 + cos α) / π, α the azimuth between f and ω; since sin θ cos α = ω·f,
///   w = (sin θ + ω·f) / π. A point source: I sin θ (1 + cos α) / (π d²).
/// Under a uniform radiance L all round, each reads π L (∫ sin θ dω = π², and ∫ ω·f dω = 0).
/// The cylinder draws uniform directions on the sphere (density 1/4π; w/p = 4 sin θ). The semi-cylinder draws
/// cos θ uniformly and α from the cardioid (1 + cos α)/2π, density (1 + cos α)/4π per steradian (dω = d(cos θ) dα),
/// so w/p = 4 sin θ again and its variance is the cylinder's; both reach every direction w counts.
struct MeterReceptor {
  enum class Shape { plane, cylinder, semi_cylinder };
  Shape shape = Shape::plane;
  Vec3 direction;  ///< unit: the plane's normal, or the cylinder's axis
  Vec3 facing;     ///< unit, ⟂ direction: the semi-cylinder's facing; unused otherwise

  /// w(ω) for a unit ω.
  float response(Vec3 wi) const {
    if (shape == Shape::plane) return std::max(0.0f, dot(wi, direction));
    const float sin_theta = length(cross(wi, direction));  // not √(1 − cos²): that cancels near the axis
    const float around = shape == Shape::cylinder ? sin_theta : std::max(0.0f, sin_theta + dot(wi, facing));
    return around * std::numbers::inv_pi_v<float>;
  }

  /// The density of sample_direction at ω, per steradian.
  float direction_pdf(Vec3 wi) const {
    if (shape == Shape::plane) return cosine_hemisphere_pdf(std::max(0.0f, dot(wi, direction)));
    const float uniform = 0.25f * std::numbers::inv_pi_v<float>;
    if (shape == Shape::cylinder) return uniform;
    const float sin_theta = length(cross(wi, direction));
    if (!(sin_theta > 1e-6f)) return uniform;  // along the axis α is undefined; a set of measure zero
    return uniform * std::clamp(1.0f + dot(wi, facing) / sin_theta, 0.0f, 2.0f);
  }

  /// A direction for the estimator's BSDF-like technique, from u ∈ [0,1)².
  Vec3 sample_direction(Vec2 u) const {
    if (shape == Shape::plane) return Frame::from_normal(direction).to_world(sample_cosine_hemisphere(u));
    const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    if (shape == Shape::cylinder) {
      const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
      return Frame::from_normal(direction).to_world({r * std::cos(phi), r * std::sin(phi), z});
    }
    const float alpha = sample_cardioid_angle(u.y);
    const Vec3 side = cross(direction, facing);
    return facing * (r * std::cos(alpha)) + side * (r * std::sin(alpha)) + direction * z;
  }

  /// α ∈ [−π, π] with density (1 + cos α)/2π from u ∈ [0,1): the root of F(α) = (α + sin α + π)/2π = u, by Newton's
  /// method kept inside a bisection bracket (F is increasing; F' vanishes only at ±π).
  static float sample_cardioid_angle(float u) {
    const double pi = std::numbers::pi, target = 2.0 * pi * double(u) - pi;
    double lo = -pi, hi = pi, alpha = 0.5 * target;  // α + sin α ≈ 2α near 0
    for (int i = 0; i < 40; ++i) {
      const double g = alpha + std::sin(alpha) - target;
      if (std::fabs(g) < 1e-12) break;
      (g > 0.0 ? hi : lo) = alpha;
      const double slope = 1.0 + std::cos(alpha);
      double next = slope > 1e-12 ? alpha - g / slope : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      alpha = next;
    }
    return float(alpha);
  }

  /// The geometric normal the light sampler and ray offsets are given: the plane's, or none (zero) for a cylinder,
  /// which takes light from every side.
  Vec3 surface_normal() const { return shape == Shape::plane ? direction : Vec3{0.0f, 0.0f, 0.0f}; }
};

}  // namespace rimu
