// What a goniometric point light needs of its intensity distribution I(ω) over the sphere (in the light's local
// frame, ω unit): the value, its integral, a sampling routine with its density, and the cone of directions where it
// can be non-zero. Two kinds: CandelaDistribution (a (γ, C) table, IES LM-63) and EqualAreaIntensity (pbrt-v4's
// equal-area octahedral image).
#pragma once

#include <optional>

#include "transport/geometry/vector.h"

namespace rimu {

class IntensityDistribution {
 public:
  virtual ~IntensityDistribution() = default;

  /// I at local direction `w` (unit); ≥ 0.
  virtual double intensity(Vec3 w) const = 0;
  /// ∫ I dω over the sphere (lm for a candela table), exact for the distribution's own interpolation.
  virtual double integral_sr() const = 0;
  /// The largest value I takes.
  virtual double peak() const = 0;

  struct DirectionSample {
    Vec3 w;     ///< local, unit
    float pdf;  ///< solid-angle density, > 0
  };
  /// A local direction drawn with density pdf(w) (≈ or = I/∫I); std::nullopt if I is zero everywhere.
  virtual std::optional<DirectionSample> sample(Vec2 u) const = 0;
  /// The solid-angle density sample() has at local direction `w`.
  virtual float pdf(Vec3 w) const = 0;

  /// [γ_min, γ_max] (radians from local +z) outside which I is 0; std::nullopt if I is zero everywhere.
  virtual std::optional<std::pair<double, double>> nonzero_gamma_rad() const = 0;
};

}  // namespace rimu
