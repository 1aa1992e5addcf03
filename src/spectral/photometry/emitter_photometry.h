// The geometric conventions that turn a light's amount into the quantity its class takes, and back into every
// other unit (docs/light-units.md has a worked example of each).
//
// Each light class is built from one spectral quantity (transport/lights/light_spectrum.h): point and spot lights from an
// intensity I, distant lights from an irradiance E at normal incidence, area and environment lights from a radiance
// L. A power Φ becomes one of these through the light's geometry:
//   point                 I = Φ / 4π
//   spot, "cone"          I = Φ / (2π (1 − (cos θ_inner + cos θ_outer)/2))   the lamp's lumens are all in its cone,
//                         with the smoothstep falloff of spot_light.h (its exact solid-angle integral)
//   spot, "point"         I = Φ / 4π   lumens "as if it were a point light" (the on-axis intensity does not change
//                         when the cone is narrowed; what several engines do)
//   area, one-sided       L = Φ / (π A)   a Lambertian emitter: ∫ L cos θ dω over the hemisphere is π L, times A
//   area, two-sided       L = Φ / (2π A)  the same power split over both faces
// where A is the area of the mesh in world space, after its transform (scaling a 1 m² quad by 2 makes it 4 m², and
// keeps its lumens by dividing its luminance by 4). An exposure value at ISO 100 is a luminance for area and
// environment lights (reflected-light meter, K = 12.5) and an illuminance for distant lights (incident meter, C = 250).
#pragma once

#include "spectral/photometry/light_units.h"

namespace rimu {

/// `medium`: an emissive medium, whose amount is the luminance of an optically thick body of it (MediumEmission).
enum class EmitterKind { point, spot, distant, area, environment, medium };

/// How a spot light's power relates to its intensity (see above).
enum class SpotPowerConvention { cone, point };

/// Which quantity stays fixed when the light's spectral shape changes.
enum class KeepConstant {
  photometric,  ///< the amount is lm/cd/lx/nt of the light as it is (the default)
  radiometric,  ///< a photometric amount is turned into watts with a reference shape's efficacy, then the watts stay
};

/// The shape of an emitter as far as unit conversions care.
struct EmitterGeometry {
  EmitterKind kind = EmitterKind::point;
  double inner_half_angle_deg = 0, outer_half_angle_deg = 0;  ///< spot lights
  SpotPowerConvention spot_power = SpotPowerConvention::cone;
  double area_m2 = 0;        ///< area lights: world-space area after the transform
  bool two_sided = false;    ///< area lights

  /// Φ/I in sr for point and spot lights (4π, or the spot's effective cone); 0 for the others.
  double power_per_intensity_sr() const;
  /// Φ/L in m²·sr for area lights (π A per emitting side); 0 for the others.
  double power_per_radiance_m2_sr() const;
  /// "point", "spot", "distant", "area", "environment".
  const char* kind_name() const;
};

/// The spot falloff s(cos θ) of transport/lights/spot_light.h: 1 inside the inner cone, 0 outside the outer one, the
/// smoothstep t²(3 − 2t) in cos θ between.
double spot_falloff(double cos_theta, double cos_inner, double cos_outer);

/// The quantity the light's class is built from (I, E or L), in the amount's family (photometric or radiometric).
struct NativeAmount {
  double value = 0;
  bool photometric = true;
};
/// Converts `amount` through the geometry's convention. Throws InputError at `where` when the unit does not apply to
/// the kind (e.g. lux for a point light), naming the units that do.
NativeAmount native_amount(LightAmount amount, const EmitterGeometry& geometry, const SourceLocation& where);

/// The scale of the light's shape: native / (K_m ΣSVΔλ) for a photometric amount, native / ∫S dλ for a radiometric
/// one. With KeepConstant::radiometric and a photometric amount, the native amount is first turned into watts with
/// `reference`'s efficacy (the shape the amount was authored for), so changing `shape` keeps the watts.
double shape_scale(LightAmount amount, const EmitterGeometry& geometry, const ShapeIntegrals& shape,
                   const SourceLocation& where, KeepConstant keep = KeepConstant::photometric,
                   const ShapeIntegrals* reference = nullptr);

/// A light's output in every unit that applies to it (the others are 0).
struct EmitterOutput {
  double efficacy_lm_W = 0;                                     ///< of radiation, of the shape
  double radiant_power_w = 0, luminous_power_lm = 0;            ///< point, spot, area
  double radiant_intensity_w_sr = 0, luminous_intensity_cd = 0; ///< point, spot (on axis)
  double irradiance_w_m2 = 0, illuminance_lx = 0;               ///< distant, at normal incidence
  double radiance_w_m2_sr = 0, luminance_nt = 0;                ///< area, environment
  double ev100 = 0;  ///< luminance (area, environment) or illuminance (distant) as EV at ISO 100; 0 for the others
};
/// Everything about scale × shape on `geometry`.
EmitterOutput emitter_output(const EmitterGeometry& geometry, double scale, const ShapeIntegrals& shape);

/// Illuminance (lx) on a surface facing a point or spot light at `distance_m`, `off_axis_deg` from a spot's axis:
/// E = I s(θ) / d². Photometric counterpart of the irradiance the renderer computes.
double illuminance_at_lx(const EmitterGeometry& geometry, const EmitterOutput& output, double distance_m,
                         double off_axis_deg);

}  // namespace rimu
