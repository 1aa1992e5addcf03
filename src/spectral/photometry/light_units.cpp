#include "spectral/photometry/light_units.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {
namespace {

struct UnitSpelling {
  std::string_view symbol;
  LightUnit unit;
};

// Every accepted spelling; the first one of each unit is the canonical symbol that unit_symbol() prints.
constexpr std::array kSpellings{
    UnitSpelling{"lm", LightUnit::lumen},          UnitSpelling{"W", LightUnit::watt},
    UnitSpelling{"cd", LightUnit::candela},        UnitSpelling{"W/sr", LightUnit::watt_per_sr},
    UnitSpelling{"lx", LightUnit::lux},            UnitSpelling{"W/m2", LightUnit::watt_per_m2},
    UnitSpelling{"nt", LightUnit::nit},            UnitSpelling{"W/m2/sr", LightUnit::watt_per_m2_sr},
    UnitSpelling{"EV", LightUnit::ev100},          UnitSpelling{"lumen", LightUnit::lumen},
    UnitSpelling{"lumens", LightUnit::lumen},      UnitSpelling{"w", LightUnit::watt},
    UnitSpelling{"candela", LightUnit::candela},   UnitSpelling{"lux", LightUnit::lux},
    UnitSpelling{"W/m²", LightUnit::watt_per_m2},  UnitSpelling{"nits", LightUnit::nit},
    UnitSpelling{"nit", LightUnit::nit},           UnitSpelling{"cd/m2", LightUnit::nit},
    UnitSpelling{"cd/m²", LightUnit::nit},         UnitSpelling{"W/m²/sr", LightUnit::watt_per_m2_sr},
    UnitSpelling{"W/(m2·sr)", LightUnit::watt_per_m2_sr}, UnitSpelling{"W/(m2 sr)", LightUnit::watt_per_m2_sr},
    UnitSpelling{"ev", LightUnit::ev100},          UnitSpelling{"EV100", LightUnit::ev100},
};

}  // namespace

std::string unit_symbol(LightUnit unit) {
  for (const UnitSpelling& s : kSpellings)
    if (s.unit == unit) return std::string(s.symbol);
  return "?";
}

bool is_photometric(LightUnit unit) {
  switch (unit) {
    case LightUnit::lumen:
    case LightUnit::candela:
    case LightUnit::lux:
    case LightUnit::nit:
    case LightUnit::ev100: return true;
    default: return false;
  }
}

LightQuantity quantity_of(LightUnit unit) {
  switch (unit) {
    case LightUnit::lumen:
    case LightUnit::watt: return LightQuantity::power;
    case LightUnit::candela:
    case LightUnit::watt_per_sr: return LightQuantity::intensity;
    case LightUnit::lux:
    case LightUnit::watt_per_m2: return LightQuantity::irradiance;
    case LightUnit::nit:
    case LightUnit::watt_per_m2_sr: return LightQuantity::radiance;
    case LightUnit::ev100: return LightQuantity::exposure_value;
  }
  return LightQuantity::power;
}

LightUnit unit_of(LightQuantity quantity, bool photometric) {
  switch (quantity) {
    case LightQuantity::power: return photometric ? LightUnit::lumen : LightUnit::watt;
    case LightQuantity::intensity: return photometric ? LightUnit::candela : LightUnit::watt_per_sr;
    case LightQuantity::irradiance: return photometric ? LightUnit::lux : LightUnit::watt_per_m2;
    case LightQuantity::radiance: return photometric ? LightUnit::nit : LightUnit::watt_per_m2_sr;
    case LightQuantity::exposure_value: return LightUnit::ev100;
  }
  return LightUnit::lumen;
}

LightUnit parse_light_unit(std::string_view symbol, const SourceLocation& where) {
  for (const UnitSpelling& s : kSpellings)
    if (s.symbol == symbol) return s.unit;
  throw InputError(where, "unknown unit '" + std::string(symbol) +
                              "'; expected one of lm, W, cd, W/sr, lx, W/m2, nt, W/m2/sr, EV");
}

LightAmount parse_light_amount(std::string_view text, const SourceLocation& where) {
  const std::string s(text);
  const char* begin = s.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(value))
    throw InputError(where, "expected a number and a unit, e.g. \"800 lm\" or \"2.5 W/sr\"; got '" + s + "'");
  std::string_view rest(end);
  while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  while (!rest.empty() && rest.back() == ' ') rest.remove_suffix(1);
  if (rest.empty()) throw InputError(where, "'" + s + "' has no unit; expected lm, W, cd, W/sr, lx, W/m2, nt, W/m2/sr or EV");
  const LightAmount amount{value, parse_light_unit(rest, where)};
  if (amount.unit != LightUnit::ev100 && !(value > 0.0))
    throw InputError(where, "a light's amount must be positive; got '" + s + "'");
  check_light_amount_range(amount, where);
  return amount;
}

void check_light_amount_range(LightAmount amount, const SourceLocation& where) {
  const bool ev = amount.unit == LightUnit::ev100;
  const double lo = ev ? kMinEv100 : kMinLightAmount, hi = ev ? kMaxEv100 : kMaxLightAmount;
  if (amount.value >= lo && amount.value <= hi) return;
  std::ostringstream message;
  message << (ev ? "an exposure value" : "a light's amount") << " must be in [" << lo << ", " << hi << "] "
          << unit_symbol(amount.unit) << "; got " << amount.value;
  throw InputError(where, message.str());
}

std::string format_light_amount(LightAmount amount) {
  std::ostringstream out;
  out << amount.value << ' ' << unit_symbol(amount.unit);
  return out.str();
}

ShapeIntegrals shape_integrals(const Spectrum& shape, const TabulatedSpectrum& v) {
  ShapeIntegrals result;
  const int steps = int(kLambdaMaxNm - kLambdaMinNm);
  double trapezoid = 0.5 * (shape.value(kLambdaMinNm) + shape.value(kLambdaMaxNm));
  for (int i = 1; i < steps; ++i) trapezoid += shape.value(kLambdaMinNm + i);
  result.radiant = trapezoid;  // × 1 nm
  result.luminous = kMaxLuminousEfficacy_lm_W *
                    integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) { return shape.value(l) * v.value(l); });
  if (!std::isfinite(result.radiant) || !std::isfinite(result.luminous))
    throw InputError({}, "the spectrum '" + shape.describe() + "' overflows: its integral over 360-830 nm is not a "
                         "finite number; give its values in a smaller unit");
  if (!(result.radiant > 0.0))
    throw InputError({}, "the spectrum '" + shape.describe() + "' has no power in 360-830 nm, so no amount can scale it");
  if (!(result.luminous > 0.0))
    throw InputError({}, "the spectrum '" + shape.describe() +
                             "' has no visible power (it is zero wherever V(λ) is not), so it cannot be normalised to "
                             "lumens, candela, lux or nits; give the amount in W, W/sr, W/m2 or W/m2/sr instead");
  return result;
}

double shape_scale(const ShapeIntegrals& integrals, LightAmount amount, const SourceLocation& where) {
  const double value = amount.unit == LightUnit::ev100 ? luminance_nt_from_ev100(amount.value) : amount.value;
  const double scale = value / (is_photometric(amount.unit) ? integrals.luminous : integrals.radiant);
  if (!(std::isfinite(scale) && scale > 0.0))
    throw InputError(where, "the factor that gives this spectrum " + format_light_amount(amount) +
                                " is not a finite number: the spectrum's values are too small; give them in a "
                                "larger unit");
  return scale;
}

double luminance_nt_from_ev100(double ev100) { return kReflectedMeterConstant / 100.0 * std::exp2(ev100); }
double ev100_from_luminance_nt(double luminance_nt) { return std::log2(100.0 * luminance_nt / kReflectedMeterConstant); }
double illuminance_lx_from_ev100(double ev100) { return kIncidentMeterConstant / 100.0 * std::exp2(ev100); }
double ev100_from_illuminance_lx(double illuminance_lx) {
  return std::log2(100.0 * illuminance_lx / kIncidentMeterConstant);
}

}  // namespace rimu
