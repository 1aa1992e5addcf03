// Light amounts: units, the shape integrals, the geometric conventions of each light, EV, and "keep".
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/photometry/emitter_photometry.h"
#include "spectral/photometry/light_units.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;
double cos_deg(double d) { return std::cos(d * kPi / 180.0); }

ShapeIntegrals integrals_of(const Spectrum& s) { return shape_integrals(s, test::library().photopic_v()); }

}  // namespace

TEST_CASE("light amounts: number and unit, with clear errors") {
  const LightAmount a = parse_light_amount("800 lm", {});
  CHECK(a.value == 800.0);
  CHECK(a.unit == LightUnit::lumen);
  CHECK(parse_light_amount("2.5W/sr", {}).unit == LightUnit::watt_per_sr);
  CHECK(parse_light_amount("100 cd/m2", {}).unit == LightUnit::nit);
  CHECK(parse_light_amount("-2 EV", {}).value == -2.0);  // EV may be negative: a dim scene
  CHECK(format_light_amount({1600, LightUnit::candela}) == "1600 cd");
  CHECK_THROWS_WITH_AS(parse_light_amount("-3 lm", {"", 0, "--from"}), doctest::Contains("must be positive"), InputError);
  CHECK_THROWS_WITH_AS(parse_light_amount("0 W", {}), doctest::Contains("must be positive"), InputError);
  CHECK_THROWS_WITH_AS(parse_light_amount("5 furlongs", {}), doctest::Contains("unknown unit 'furlongs'"), InputError);
  CHECK_THROWS_WITH_AS(parse_light_amount("lm", {}), doctest::Contains("expected a number and a unit"), InputError);
  CHECK_THROWS_WITH_AS(parse_light_amount("12", {}), doctest::Contains("has no unit"), InputError);
}

TEST_CASE("shape integrals: the equal-energy spectrum and a line at 555 nm") {
  // ∫1 dλ over 360-830 nm = 470 nm (trapezoid, exact); K_m Σ V Δλ = 683 × 106.856917 (Σȳ at 1 nm of CIE 1931,
  // tests/spectral/colorimetry_test.cpp). Both are sums of table values: agreement to 1e-9 is rounding.
  const ShapeIntegrals e = integrals_of(ConstantSpectrum(1.0));
  CHECK(e.radiant == doctest::Approx(470.0).epsilon(1e-12));
  CHECK(e.luminous == doctest::Approx(683.0 * 106.856917).epsilon(1e-8));
  // A line at 555 nm, where V = 1.000000 (CIE 1924 table): K = K_m = 683 lm/W exactly (the definition of K_m).
  const TabulatedSpectrum line({554.0, 555.0, 556.0}, {0.0, 1.0, 0.0}, Extrapolation::zero, "line at 555 nm");
  CHECK(integrals_of(line).efficacy_lm_W() == doctest::Approx(683.0).epsilon(1e-12));
  CHECK_THROWS_WITH_AS(integrals_of(ConstantSpectrum(0.0)), doctest::Contains("no power"), InputError);
}

TEST_CASE("point light: 1000 lm is 1000/4π cd, and back") {
  // I = Φ/4π (isotropic). Round trip through the shape's integrals is exact to rounding (1e-12).
  const BlackbodySpectrum warm(2700.0, BlackbodySpectrum::Scale::peak_one);
  const ShapeIntegrals s = integrals_of(warm);
  const EmitterGeometry point{EmitterKind::point};
  const double scale = shape_scale({1000.0, LightUnit::lumen}, point, s, {});
  const EmitterOutput out = emitter_output(point, scale, s);
  CHECK(out.luminous_intensity_cd == doctest::Approx(1000.0 / (4.0 * kPi)).epsilon(1e-12));
  CHECK(out.luminous_power_lm == doctest::Approx(1000.0).epsilon(1e-12));
  CHECK(out.radiant_power_w == doctest::Approx(1000.0 / s.efficacy_lm_W()).epsilon(1e-12));
  // Illuminance at 2 m facing the lamp: E = I/d² = 1000/(16π) lx.
  CHECK(illuminance_at_lx(point, out, 2.0, 0.0) == doctest::Approx(1000.0 / (16.0 * kPi)).epsilon(1e-12));
  // The same light given in watts: Φe = 1000/K W.
  CHECK(shape_scale({out.radiant_power_w, LightUnit::watt}, point, s, {}) == doctest::Approx(scale).epsilon(1e-12));
}

TEST_CASE("spot light: lumens over its cone or as if it were a point") {
  // Cone 40° (half-angle 20°), full intensity to 15°: the closed form of spot_light.h against Simpson's rule on the
  // falloff itself, 2π ∫ s(cos θ) sin θ dθ (smooth integrand, 2000 intervals: error < 1e-10).
  EmitterGeometry spot{EmitterKind::spot, 15.0, 20.0, SpotPowerConvention::cone};
  const double closed = spot.power_per_intensity_sr();
  double simpson = 0.0;
  const int n = 2000;
  const double h = (20.0 * kPi / 180.0) / n;
  for (int i = 0; i <= n; ++i) {
    const double theta = i * h;
    const double f = spot_falloff(std::cos(theta), cos_deg(15.0), cos_deg(20.0)) * std::sin(theta);
    simpson += (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * f;
  }
  simpson *= 2.0 * kPi * h / 3.0;
  CHECK(closed == doctest::Approx(simpson).epsilon(1e-8));
  CHECK(closed == doctest::Approx(2.0 * kPi * (1.0 - 0.5 * (cos_deg(15.0) + cos_deg(20.0)))).epsilon(1e-15));

  const ShapeIntegrals s = integrals_of(ConstantSpectrum(1.0));
  const double cone_scale = shape_scale({800.0, LightUnit::lumen}, spot, s, {});
  CHECK(emitter_output(spot, cone_scale, s).luminous_intensity_cd == doctest::Approx(800.0 / closed).epsilon(1e-12));
  spot.spot_power = SpotPowerConvention::point;
  const double point_scale = shape_scale({800.0, LightUnit::lumen}, spot, s, {});
  const EmitterOutput as_point = emitter_output(spot, point_scale, s);
  CHECK(as_point.luminous_intensity_cd == doctest::Approx(800.0 / (4.0 * kPi)).epsilon(1e-12));
  // What the lamp really emits is only what its cone holds.
  CHECK(as_point.luminous_power_lm == doctest::Approx(800.0 * closed / (4.0 * kPi)).epsilon(1e-12));
  // 17.5° is half-way through the falloff in angle; s is the smoothstep of t = (cos θ − cos θo)/(cos θi − cos θo).
  const double t = (cos_deg(17.5) - cos_deg(20.0)) / (cos_deg(15.0) - cos_deg(20.0));
  CHECK(illuminance_at_lx(spot, as_point, 3.0, 17.5) ==
        doctest::Approx(as_point.luminous_intensity_cd * t * t * (3 - 2 * t) / 9.0).epsilon(1e-12));
}

TEST_CASE("area light: L = Φ/(πA) one-sided, Φ/(2πA) two-sided") {
  const ShapeIntegrals s = integrals_of(ConstantSpectrum(1.0));
  EmitterGeometry panel{EmitterKind::area};
  panel.area_m2 = 2.0;
  CHECK(emitter_output(panel, shape_scale({1000.0, LightUnit::lumen}, panel, s, {}), s).luminance_nt ==
        doctest::Approx(1000.0 / (2.0 * kPi)).epsilon(1e-12));
  panel.two_sided = true;
  const EmitterOutput two = emitter_output(panel, shape_scale({1000.0, LightUnit::lumen}, panel, s, {}), s);
  CHECK(two.luminance_nt == doctest::Approx(1000.0 / (4.0 * kPi)).epsilon(1e-12));
  CHECK(two.luminous_power_lm == doctest::Approx(1000.0).epsilon(1e-12));
  panel.area_m2 = 0.0;
  CHECK_THROWS_WITH_AS(shape_scale({1000.0, LightUnit::lumen}, panel, s, {}), doctest::Contains("no area"), InputError);
}

TEST_CASE("exposure values at ISO 100: reflected (K = 12.5) and incident (C = 250) meters") {
  // ISO 2720 meter equations N²/t = L S/K = E S/C with EV = log2(N²/t), S = 100: L = 0.125·2^EV nt, E = 2.5·2^EV lx.
  CHECK(luminance_nt_from_ev100(0.0) == doctest::Approx(0.125).epsilon(1e-15));
  CHECK(luminance_nt_from_ev100(15.0) == doctest::Approx(4096.0).epsilon(1e-15));
  CHECK(illuminance_lx_from_ev100(15.0) == doctest::Approx(81920.0).epsilon(1e-15));
  CHECK(ev100_from_luminance_nt(luminance_nt_from_ev100(7.3)) == doctest::Approx(7.3).epsilon(1e-14));
  CHECK(ev100_from_illuminance_lx(illuminance_lx_from_ev100(-1.5)) == doctest::Approx(-1.5).epsilon(1e-14));
  const ShapeIntegrals s = integrals_of(ConstantSpectrum(1.0));
  const EmitterGeometry sun{EmitterKind::distant};
  CHECK(emitter_output(sun, shape_scale({15.0, LightUnit::ev100}, sun, s, {}), s).illuminance_lx ==
        doctest::Approx(81920.0).epsilon(1e-12));
}

TEST_CASE("units that do not fit the light are errors naming the ones that do") {
  const ShapeIntegrals s = integrals_of(ConstantSpectrum(1.0));
  CHECK_THROWS_WITH_AS(shape_scale({100.0, LightUnit::lux}, EmitterGeometry{EmitterKind::point}, s, {"s.json", 0, "/lights/0"}),
                       doctest::Contains("a point light cannot be given in lx; use lm or W"), InputError);
  CHECK_THROWS_WITH_AS(shape_scale({100.0, LightUnit::lumen}, EmitterGeometry{EmitterKind::distant}, s, {}),
                       doctest::Contains("lx or W/m2"), InputError);
  CHECK_THROWS_WITH_AS(shape_scale({100.0, LightUnit::candela}, EmitterGeometry{EmitterKind::environment}, s, {}),
                       doctest::Contains("nt or W/m2/sr"), InputError);
  // The article follows the light's name: "an environment light", "an area light".
  CHECK_THROWS_WITH_AS(shape_scale({100.0, LightUnit::lux}, EmitterGeometry{EmitterKind::environment}, s, {}),
                       doctest::Contains("an environment light cannot be given in lx"), InputError);
}

TEST_CASE("recolouring keeps lumens, keep radiometric keeps the watts of the reference shape") {
  // 800 lm at 2700 K and at 6500 K: the same lumens, radiant power 800/K(T) each (Manuka course notes §7.6).
  const BlackbodySpectrum warm(2700.0, BlackbodySpectrum::Scale::peak_one);
  const BlackbodySpectrum cool(6500.0, BlackbodySpectrum::Scale::peak_one);
  const ShapeIntegrals w = integrals_of(warm), c = integrals_of(cool);
  const EmitterGeometry point{EmitterKind::point};
  const EmitterOutput warm_out = emitter_output(point, shape_scale({800.0, LightUnit::lumen}, point, w, {}), w);
  const EmitterOutput cool_out = emitter_output(point, shape_scale({800.0, LightUnit::lumen}, point, c, {}), c);
  CHECK(warm_out.luminous_power_lm == doctest::Approx(cool_out.luminous_power_lm).epsilon(1e-12));
  CHECK(cool_out.radiant_power_w < 0.75 * warm_out.radiant_power_w);  // 6500 K puts more of its power where V is high
  const double kept = shape_scale({800.0, LightUnit::lumen}, point, c, {}, KeepConstant::radiometric, &w);
  const EmitterOutput kept_out = emitter_output(point, kept, c);
  CHECK(kept_out.radiant_power_w == doctest::Approx(warm_out.radiant_power_w).epsilon(1e-12));
  CHECK(kept_out.luminous_power_lm == doctest::Approx(800.0 * c.efficacy_lm_W() / w.efficacy_lm_W()).epsilon(1e-12));
}
