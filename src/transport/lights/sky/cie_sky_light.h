// A CIE standard general sky as a light at infinity (transport/lights/sky/cie_standard_sky.h for the luminance
// distribution): radiance L(ω, λ) = S(λ) · L(ω)/L_z over the upper hemisphere, nothing below the horizon.
//
// S(λ) is the zenith's spectral radiance (a LightSpectrum: shape × scale set by the loader, e.g. a CIE D-series
// daylight scaled to a zenith luminance); every sky element has the same spectrum (the standard gives luminance
// only), so emitted_spectrum() is S. A ground is not part of the light: put scene geometry under the sky.
//
// Evaluation is analytic: radiance_escaped evaluates the standard's formula in double at the exact direction, so
// nothing is tabulated in what the sky emits.
//
// Sampling: a Distribution2D (transport/sampling/distribution_2d.h) over the upper hemisphere in the equal-area
// coordinates (u, v) = (φ/2π, 1 − cos θ) in the light's frame (n = up): dω = dφ d(cos θ) = 2π du dv, so
//   p_ω(ω) = p(u, v) / 2π      exactly, at every direction (no Jacobian singularity at the zenith).
// A cell's weight is the largest relative luminance at its 3 × 3 corner, edge and centre points (so the sun's
// peak is not under-sampled when it falls inside a cell) plus 10⁻³ of the mean, so the density is positive
// wherever the sky emits. The density is piecewise constant; pdf_li returns exactly the density sample_li draws
// with, the radiance is the exact formula: the estimate is unbiased and its variance is low wherever the
// luminance is close to constant on a cell (256 × 64 cells of 1.4° × 1/64 in cos θ).
//
// Portals (set_portals; transport/lights/environment_portal.h), as for an environment light: rectangles (a room's
// windows and skylights) through which the sky is known to reach the scene. sample_li then draws directions uniformly
// in the solid angle the portals subtend at the reference point (p_ω = N/ΣΩ) instead of by the sky's luminance, and
// pdf_li is that density; a direction below the horizon has no radiance and is not returned. Directions outside the
// portals are still lit through BSDF sampling (MIS weight 1 there), so the estimate stays unbiased whatever the
// portals cover; indoors nearly every light sample then reaches the sky instead of a wall. For the light tree the sky
// becomes a leaf like an area light on its portals (part_bounds), of the radiance L̄ = ∫S dλ · ∫ L/L_z cos θ dω / π
// that makes a horizontal portal pass the sky's horizontal illuminance (a vertical window passes about half of
// π L̄ A: the bounds only steer the choice of light).
//
// Integrals (calibration and power): ∫ L/L_z cos θ dω and ∫ L/L_z dω over the upper hemisphere by the midpoint
// rule in (φ, cos θ) on 1024 × 512 points, ~0.1 s at load. Against 8192 × 4096 points its relative error was
// ≤ 2.3e-6 for types 1, 7, 12, 13 and 15 with the sun at 3°, 30° and 75° (the clear skies' circumsolar cusp and the
// low sun are the worst cases); the tests check < 1e-5 against a grid of twice the resolution.
#pragma once

#include <array>
#include <optional>

#include "transport/geometry/frame.h"
#include "transport/lights/light.h"
#include "transport/lights/environment_portal.h"
#include "transport/lights/light_spectrum.h"
#include "transport/lights/sky/cie_standard_sky.h"
#include "transport/sampling/distribution_2d.h"

namespace rimu {

/// ∫ L/L_z cos θ dω (the diffuse horizontal illuminance per unit zenith luminance) and ∫ L/L_z dω, in sr, over the
/// upper hemisphere, for sky `p` with the sun at `sun_local` (unit, +z = zenith). `n_phi` × `n_mu` midpoints.
struct CieSkyIntegrals {
  double cosine_weighted_sr = 0;
  double solid_angle_sr = 0;
};
CieSkyIntegrals integrate_cie_sky(const CieSkyParameters& p, const std::array<double, 3>& sun_local, int n_phi = 1024,
                                  int n_mu = 512);

class CieSkyLight final : public Light {
 public:
  /// Sky type `type` in 1-15 (asserted), zenith along `up` (world, unit), the sun towards `sun_direction` (world,
  /// unit, from the scene towards the sun; may be below the horizon: the formula is then extrapolated, and the loader
  /// warns), the zenith's spectral radiance `zenith_radiance` W/(m²·sr·nm). `integrals`: integrate_cie_sky's for
  /// this type and sun elevation if the caller has them (a loader calibrating by illuminance), else computed here.
  CieSkyLight(int type, Vec3 up, Vec3 sun_direction, LightSpectrum zenith_radiance,
              std::optional<CieSkyIntegrals> integrals = std::nullopt);

  /// Restrict light sampling to directions through `portals` (see above); an empty set restores the default.
  void set_portals(PortalSet portals) { portals_ = std::move(portals); }
  const PortalSet& portals() const { return portals_; }
  const PortalSet* portal_set() const override { return portals_.empty() ? nullptr : &portals_; }

  /// A direction over the upper hemisphere by the tabulated luminance, or through the portals (see above); distance ∞.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  /// p_ω(wi) = p(u, v)/2π (with portals: N/ΣΩ at ref) above the horizon, 0 below it. `hit` is ignored.
  float pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit = nullptr) const override;
  /// S(λ) · L(ω)/L_z above the horizon, 0 below.
  SampledSpectrum radiance_escaped(Vec3 direction, const SampledWavelengths& lambda) const override;
  /// Power entering a sphere of radius r: π r² ∫S dλ ∫ L/L_z dω (each direction's radiance crosses a disc of πr²);
  /// with portals π L̄ A, A their total area (see above), whatever the radius.
  double total_power_w(double scene_radius_m) const override;
  /// With portals: the portals as a two-sided area light of radiance L̄ (see above); without, std::nullopt.
  std::optional<LightBounds> part_bounds(int part) const override;
  bool is_infinite() const override { return true; }
  const LightSpectrum* emitted_spectrum() const override { return &zenith_radiance_; }

  /// L(ω)/L_z for a world direction (0 below the horizon).
  double relative_luminance(Vec3 direction) const;
  /// The integrals above for this sky and sun.
  const CieSkyIntegrals& integrals() const { return integrals_; }
  int type() const { return type_; }

  /// (u, v) of a world direction above the horizon, and back (see above).
  Vec2 direction_to_uv(Vec3 direction) const;
  Vec3 uv_to_direction(Vec2 uv) const;

 private:
  double portal_radiance_w_m2_sr() const;  // L̄ of the portals' bounds and power (see above)

  int type_;
  const CieSkyParameters& parameters_;
  Frame frame_;                    // n = up
  std::array<double, 3> sun_local_;
  std::optional<CieSkyLuminance> luminance_;  // set in the constructor, once the sun is in the light's frame
  LightSpectrum zenith_radiance_;
  CieSkyIntegrals integrals_;
  Distribution2D distribution_;
  PortalSet portals_;  // empty: the whole hemisphere by luminance
};

}  // namespace rimu
