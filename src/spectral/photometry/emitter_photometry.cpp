#include "spectral/photometry/emitter_photometry.h"

#include <cmath>
#include <numbers>

#include "spectral/indefinite_article.h"
#include "spectral/math_constants.h"

namespace rimu {
namespace {


double cos_deg(double degrees) { return std::cos(degrees * kPi / 180.0); }

[[noreturn]] void wrong_unit(LightUnit unit, const EmitterGeometry& g, const char* allowed, const SourceLocation& where) {
  throw InputError(where, with_article(g.kind_name()) + " light cannot be given in " + unit_symbol(unit) +
                              "; use " + allowed);
}

}  // namespace

const char* EmitterGeometry::kind_name() const {
  switch (kind) {
    case EmitterKind::point: return "point";
    case EmitterKind::spot: return "spot";
    case EmitterKind::distant: return "distant";
    case EmitterKind::area: return "area";
    case EmitterKind::environment: return "environment";
    case EmitterKind::medium: return "medium";
  }
  return "?";
}

double EmitterGeometry::power_per_intensity_sr() const {
  if (kind == EmitterKind::point) return 4.0 * kPi;
  if (kind != EmitterKind::spot) return 0.0;
  if (spot_power == SpotPowerConvention::point) return 4.0 * kPi;
  // 2π ∫ s(μ) dμ with s = 1 on [cos θ_i, 1] and the smoothstep (mean 1/2) on [cos θ_o, cos θ_i] (spot_light.h).
  return 2.0 * kPi * (1.0 - 0.5 * (cos_deg(inner_half_angle_deg) + cos_deg(outer_half_angle_deg)));
}

double EmitterGeometry::power_per_radiance_m2_sr() const {
  if (kind != EmitterKind::area) return 0.0;
  return kPi * area_m2 * (two_sided ? 2.0 : 1.0);
}

double spot_falloff(double cos_theta, double cos_inner, double cos_outer) {
  if (cos_theta >= cos_inner) return 1.0;
  if (cos_theta <= cos_outer) return 0.0;
  const double t = (cos_theta - cos_outer) / (cos_inner - cos_outer);
  return t * t * (3.0 - 2.0 * t);
}

NativeAmount native_amount(LightAmount amount, const EmitterGeometry& g, const SourceLocation& where) {
  const LightQuantity q = quantity_of(amount.unit);
  const NativeAmount same{amount.value, is_photometric(amount.unit)};
  switch (g.kind) {
    case EmitterKind::point:
    case EmitterKind::spot:
      if (q == LightQuantity::intensity) return same;
      if (q == LightQuantity::power) return {amount.value / g.power_per_intensity_sr(), same.photometric};
      wrong_unit(amount.unit, g, "lm or W (power) or cd or W/sr (intensity)", where);
    case EmitterKind::distant:
      if (q == LightQuantity::irradiance) return same;
      if (q == LightQuantity::exposure_value) return {illuminance_lx_from_ev100(amount.value), true};
      wrong_unit(amount.unit, g, "lx or W/m2 (at normal incidence) or EV (incident meter at ISO 100)", where);
    case EmitterKind::area:
      if (q == LightQuantity::radiance) return same;
      if (q == LightQuantity::exposure_value) return {luminance_nt_from_ev100(amount.value), true};
      if (q == LightQuantity::power) {
        if (!(g.area_m2 > 0.0)) throw InputError(where, "the emitter has no area, so its power cannot set its luminance");
        return {amount.value / g.power_per_radiance_m2_sr(), same.photometric};
      }
      wrong_unit(amount.unit, g, "lm or W (power), nt or W/m2/sr (luminance) or EV (reflected meter at ISO 100)", where);
    case EmitterKind::environment:
    case EmitterKind::medium:
      if (q == LightQuantity::radiance) return same;
      if (q == LightQuantity::exposure_value) return {luminance_nt_from_ev100(amount.value), true};
      wrong_unit(amount.unit, g, "nt or W/m2/sr (luminance) or EV (reflected meter at ISO 100)", where);
  }
  wrong_unit(amount.unit, g, "another unit", where);
}

double shape_scale(LightAmount amount, const EmitterGeometry& geometry, const ShapeIntegrals& shape,
                   const SourceLocation& where, KeepConstant keep, const ShapeIntegrals* reference) {
  const NativeAmount native = native_amount(amount, geometry, where);
  if (!native.photometric) return native.value / shape.radiant;
  if (keep == KeepConstant::radiometric && reference) {
    const double watts = native.value / reference->efficacy_lm_W();  // what the amount meant for the reference shape
    return watts / shape.radiant;
  }
  return native.value / shape.luminous;
}

EmitterOutput emitter_output(const EmitterGeometry& g, double scale, const ShapeIntegrals& shape) {
  EmitterOutput out;
  out.efficacy_lm_W = shape.efficacy_lm_W();
  const double radiant = scale * shape.radiant, luminous = scale * shape.luminous;
  switch (g.kind) {
    case EmitterKind::point:
    case EmitterKind::spot:
      out.radiant_intensity_w_sr = radiant;
      out.luminous_intensity_cd = luminous;
      out.radiant_power_w = radiant * g.power_per_intensity_sr();
      out.luminous_power_lm = luminous * g.power_per_intensity_sr();
      if (g.kind == EmitterKind::spot && g.spot_power == SpotPowerConvention::point) {
        // The authored lumens are "as if a point"; the lamp really emits only what its cone holds.
        EmitterGeometry cone = g;
        cone.spot_power = SpotPowerConvention::cone;
        out.radiant_power_w = radiant * cone.power_per_intensity_sr();
        out.luminous_power_lm = luminous * cone.power_per_intensity_sr();
      }
      break;
    case EmitterKind::distant:
      out.irradiance_w_m2 = radiant;
      out.illuminance_lx = luminous;
      out.ev100 = ev100_from_illuminance_lx(luminous);
      break;
    case EmitterKind::area:
    case EmitterKind::environment:
    case EmitterKind::medium:
      out.radiance_w_m2_sr = radiant;
      out.luminance_nt = luminous;
      out.ev100 = ev100_from_luminance_nt(luminous);
      out.radiant_power_w = radiant * g.power_per_radiance_m2_sr();
      out.luminous_power_lm = luminous * g.power_per_radiance_m2_sr();
      break;
  }
  return out;
}

double illuminance_at_lx(const EmitterGeometry& g, const EmitterOutput& output, double distance_m, double off_axis_deg) {
  double s = 1.0;
  if (g.kind == EmitterKind::spot)
    s = spot_falloff(cos_deg(off_axis_deg), cos_deg(g.inner_half_angle_deg), cos_deg(g.outer_half_angle_deg));
  return output.luminous_intensity_cd * s / (distance_m * distance_m);
}

}  // namespace rimu
