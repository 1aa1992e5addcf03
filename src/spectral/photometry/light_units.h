// How much light a source gives: a number with a photometric or radiometric unit, and the one conversion from it
// to the scale of a light's spectral shape (docs/light-units.md).
//
// A light is shape × scale (transport/lights/light_spectrum.h). The user gives the shape (a blackbody, a CIE illuminant, a
// CSV...) and one amount in the unit natural to the light: lm or W (power), cd or W/sr (intensity), lx or W/m²
// (illuminance/irradiance), nt or W/(m²·sr) (luminance/radiance), or an exposure value at ISO 100. The scale is
//   photometric amount:  scale = amount / (K_m Σ S(λ) V(λ) Δλ)     (CIE 15:2004 eq. 7.1, k = K_m = 683 lm/W)
//   radiometric amount:  scale = amount / ∫ S(λ) dλ                 (360-830 nm)
// so that scale × S has exactly the requested photometric (or radiometric) value. It is computed once, at load.
#pragma once

#include <string>
#include <string_view>

#include "spectral/error.h"
#include "spectral/spectra/spectrum.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

/// The units a light's amount may be given in.
enum class LightUnit {
  lumen,            ///< lm, luminous power
  watt,             ///< W, radiant power
  candela,          ///< cd = lm/sr, luminous intensity
  watt_per_sr,      ///< W/sr, radiant intensity
  lux,              ///< lx = lm/m², illuminance
  watt_per_m2,      ///< W/m², irradiance
  nit,              ///< nt = cd/m², luminance
  watt_per_m2_sr,   ///< W/(m²·sr), radiance
  ev100,            ///< exposure value at ISO 100: a luminance (reflected meter) or an illuminance (incident meter)
};

/// What a unit measures, regardless of its family.
enum class LightQuantity { power, intensity, irradiance, radiance, exposure_value };

/// A number with its unit, e.g. 800 lm.
struct LightAmount {
  double value = 0;
  LightUnit unit = LightUnit::lumen;
};

/// The range an amount may take wherever a light is given (a scene, a light definition, a command line): positive
/// amounts in [1e-30, 1e30] of their unit, exposure values in [-50, 50] (2^±50 covers starlight to the sun's disc
/// many times over). Inside it every derived quantity stays a finite double.
inline constexpr double kMinLightAmount = 1e-30;
inline constexpr double kMaxLightAmount = 1e30;
inline constexpr double kMinEv100 = -50.0;
inline constexpr double kMaxEv100 = 50.0;
/// Throws InputError at `where` (with the range) if `amount` is outside the range above or not finite.
void check_light_amount_range(LightAmount amount, const SourceLocation& where);

/// "lm", "W/sr", "EV"...
std::string unit_symbol(LightUnit unit);
/// True for lm, cd, lx, nt and EV (converted through V(λ)); false for the radiometric units.
bool is_photometric(LightUnit unit);
/// What the unit measures.
LightQuantity quantity_of(LightUnit unit);
/// The unit of `quantity` in the photometric or radiometric family (exposure_value has no radiometric twin).
LightUnit unit_of(LightQuantity quantity, bool photometric);

/// A unit from its symbol: lm, W, cd, W/sr, lx, W/m2 (or W/m²), nt (or cd/m2), W/m2/sr (or W/(m2·sr)), EV.
/// Throws InputError at `where` listing the known symbols.
LightUnit parse_light_unit(std::string_view symbol, const SourceLocation& where);
/// "800 lm", "2.5W/sr", "12 EV": a finite number and a unit. Throws InputError at `where` for anything else, and for
/// an amount outside check_light_amount_range().
LightAmount parse_light_amount(std::string_view text, const SourceLocation& where);
/// "800 lm".
std::string format_light_amount(LightAmount amount);

/// The two integrals of a spectral shape S that every conversion divides by.
struct ShapeIntegrals {
  double radiant = 0;   ///< ∫ S dλ over 360-830 nm, trapezoid at 1 nm (LightSpectrum::integral_360_830's rule)
  double luminous = 0;  ///< K_m Σ S V Δλ over 360-830 nm at 1 nm (CIE 15's rectangle sum; photometry.h's rule)
  /// K = luminous / radiant, lm/W.
  double efficacy_lm_W() const { return luminous / radiant; }
};
/// Both integrals of `shape`; `v` is the CIE 1924 V(λ) (SpectralLibrary::photopic_v()). Cost: two 471-point sums.
ShapeIntegrals shape_integrals(const Spectrum& shape, const TabulatedSpectrum& v);

/// The factor that gives a shape with these integrals `amount`: amount / luminous for photometric units (an EV read
/// as a luminance), amount / radiant for radiometric ones. Throws InputError at `where` if the factor is not a
/// finite positive number (a shape so faint that even the smallest amount overflows it).
double shape_scale(const ShapeIntegrals& integrals, LightAmount amount, const SourceLocation& where);

/// Reflected-light meter calibration constant K (ISO 2720:1974; 12.5 as Canon, Nikon and Sekonic use), cd·s/m².
inline constexpr double kReflectedMeterConstant = 12.5;
/// Incident-light meter calibration constant C for a flat receptor (ISO 2720:1974 allows 240-400; 250 is usual), lx·s.
inline constexpr double kIncidentMeterConstant = 250.0;

/// The scene luminance a reflected-light meter reads as EV at ISO 100: L = (K/100)·2^EV nt (ISO 2720 meter equation
/// N²/t = L·S/K with S = 100 and EV = log2(N²/t)). EV 0 ↔ 0.125 nt.
double luminance_nt_from_ev100(double ev100);
/// The inverse: EV = log2(100 L / K).
double ev100_from_luminance_nt(double luminance_nt);
/// The illuminance an incident-light meter reads as EV at ISO 100: E = (C/100)·2^EV lx (N²/t = E·S/C). EV 0 ↔ 2.5 lx.
double illuminance_lx_from_ev100(double ev100);
/// The inverse: EV = log2(100 E / C).
double ev100_from_illuminance_lx(double illuminance_lx);

}  // namespace rimu
