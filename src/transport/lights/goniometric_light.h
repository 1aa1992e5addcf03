// A goniometric point light (an IES LM-63 photometric file's luminaire, or pbrt-v4's equal-area image): spectral
// intensity
//   I(λ, ω) = shape(λ) · table(ω)
// from one position, where table is an IntensityDistribution in the light's own frame — for a CandelaDistribution
// γ from `axis`, C around it from `c0_direction`, counter-clockwise seen from the side the axis points away from, as
// LM-63 type C measures it looking down on a downlight — and shape is a LightSpectrum in W/(sr·nm) per unit of the
// table (the scene loader scales it so one table unit is one candela, or applies a lumen or candela scale).
#pragma once

#include <memory>

#include "transport/lights/intensity_distribution.h"
#include "transport/geometry/frame.h"
#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"
#include "transport/lights/luminous_opening.h"

namespace rimu {

class GoniometricLight final : public Light {
 public:
  /// `axis` (γ = 0, unit) and `c0_direction` (C = 0; only its part perpendicular to the axis counts, and it must
  /// not be parallel to the axis) in world space.
  GoniometricLight(Vec3 position_m, Vec3 axis, Vec3 c0_direction, LightSpectrum per_unit_intensity,
                   std::shared_ptr<const IntensityDistribution> table);
  /// The table's local x, y, z are `frame`'s s, t, n in world space (orthonormal; may be left-handed, as a
  /// mirrored pbrt light transform is).
  GoniometricLight(Vec3 position_m, Frame frame, LightSpectrum per_unit_intensity,
                   std::shared_ptr<const IntensityDistribution> table);

  /// The direction to the light; radiance field shape(λ)·table(−wi)/d², pdf 1, is_delta (with an opening: to a point
  /// on it drawn from u, times the opening's weight). std::nullopt at the light or where the table is 0.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  float pdf_li(const LightReference&, Vec3, const SurfaceHit*) const override { return 0.0f; }
  /// Φ = ∫shape dλ · ∫table dω.
  double total_power_w(double scene_radius_m) const override;
  bool is_delta() const override { return true; }
  bool samples_emission() const override;
  std::optional<EmissionSample> sample_emission(float u_part, Vec2 u_position, Vec2 u_direction,
                                                const SampledWavelengths& lambda) const override;
  EmissionDensity emission_density(Vec3 normal, Vec3 direction) const override;
  /// The luminaire's position (the opening's centre).
  std::optional<Vec3> emission_centre_m(int) const override { return position_m_; }

  /// The table's peak times ∫shape dλ, in the narrowest cone about ±axis outside which the table is 0
  /// (IntensityDistribution::nonzero_gamma_rad), over the opening's bounding box.
  std::optional<LightBounds> part_bounds(int part) const override;

  /// An emission direction (world space) drawn proportionally to the table (CandelaDistribution::sample), with its
  /// solid-angle density; for light tracing and for tests.
  std::optional<IntensityDistribution::DirectionSample> sample_emission_direction(Vec2 u) const;
  /// The table's value towards world direction `w_out` (unit, away from the light).
  double table_value(Vec3 w_out) const { return table_->intensity(frame_.to_local(w_out)); }
  const IntensityDistribution& table() const { return *table_; }

  const LightSpectrum* emitted_spectrum() const override { return &per_unit_intensity_; }

  /// The surface the light leaves from (see above); a point by default.
  void set_opening(LuminousOpening opening) { opening_ = opening; }
  const LuminousOpening& opening() const { return opening_; }

 private:
  Vec3 position_m_;
  Frame frame_;  // s: C = 0, t: C = 90°, n: γ = 0
  LightSpectrum per_unit_intensity_;
  std::shared_ptr<const IntensityDistribution> table_;
  LuminousOpening opening_;
};

}  // namespace rimu
