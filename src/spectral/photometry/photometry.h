// Radiometric and photometric quantities, and the conversion between them through a spectrum's shape.
//
// Each radiometric quantity has a photometric twin that weights the same power by the eye's response. The
// pairing follows the units table in Fascione et al., "Manuka: A batch-shading architecture for spectral path
// tracing in movie production", ACM TOG 37(3), 2018; the names and symbols are those of CIE S 017:2020:
//
//   radiant power      Φe  W            ↔  luminous power      Φv  lm
//   radiant intensity  Ie  W/sr         ↔  luminous intensity  Iv  cd = lm/sr
//   irradiance         Ee  W/m²         ↔  illuminance         Ev  lx = lm/m²
//   radiance           Le  W/(m²·sr)    ↔  luminance           Lv  nt = cd/m²
//
// For a spectral distribution S(λ) scaled so that ∫S dλ is the radiometric quantity, the photometric one is
// K_m ∫ S(λ) V(λ) dλ (CIE 15:2004 eq. 7.1 with k = K_m). Both are linear in S, so for a fixed spectral *shape*
// their ratio is one number, the luminous efficacy of radiation K = K_m ∫ S V dλ / ∫ S dλ (lm/W), and every
// conversion below is a multiplication or division by K.
//
// Each quantity is its own type with an explicit constructor, so a value in lux cannot be passed where nits
// are expected, and a bare double never becomes a quantity by accident.
#pragma once

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/spectra/spectrum.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

/// Radiant power (flux) Φe in watts.
struct RadiantPower {
  explicit constexpr RadiantPower(double watts) : w(watts) {}
  double w;
};
/// Luminous power (flux) Φv in lumens.
struct LuminousPower {
  explicit constexpr LuminousPower(double lumens) : lm(lumens) {}
  double lm;
};
/// Radiant intensity Ie in W/sr.
struct RadiantIntensity {
  explicit constexpr RadiantIntensity(double watts_per_sr) : w_sr(watts_per_sr) {}
  double w_sr;
};
/// Luminous intensity Iv in candelas (lm/sr).
struct LuminousIntensity {
  explicit constexpr LuminousIntensity(double candelas) : cd(candelas) {}
  double cd;
};
/// Irradiance Ee in W/m².
struct Irradiance {
  explicit constexpr Irradiance(double watts_per_m2) : w_m2(watts_per_m2) {}
  double w_m2;
};
/// Illuminance Ev in lux (lm/m²).
struct Illuminance {
  explicit constexpr Illuminance(double lux) : lx(lux) {}
  double lx;
};
/// Radiance Le in W/(m²·sr).
struct Radiance {
  explicit constexpr Radiance(double watts_per_m2_sr) : w_m2_sr(watts_per_m2_sr) {}
  double w_m2_sr;
};
/// Luminance Lv in nits (cd/m²).
struct Luminance {
  explicit constexpr Luminance(double nits) : nt(nits) {}
  double nt;
};

/// Luminous efficacy of radiation K in lm/W: lumens per radiant watt for one spectral shape.
/// Scotopic efficacies (scotopic lm per W) use the same type; do not mix them with photopic ones.
struct LuminousEfficacy {
  explicit constexpr LuminousEfficacy(double lumens_per_watt) : lm_W(lumens_per_watt) {}
  double lm_W;
};

/// Photopic luminous efficacy of radiation of `spectrum`'s shape: K = K_m Σ S V Δλ / Σ S Δλ over `grid`, with
/// K_m = 683 lm/W and `v` the CIE 1924 V(λ) (SpectralLibrary::photopic_v()). The result depends on the grid's
/// range as well as the shape (radiant power outside the grid is not counted). Throws InputError if Σ S Δλ is
/// not positive and finite, or if the spectrum has no power where V is non-zero.
LuminousEfficacy luminous_efficacy_of_radiation_lm_W(const Spectrum& spectrum, const TabulatedSpectrum& v,
                                                     IntegrationGrid grid = IntegrationGrid::cie_1nm());

/// Scotopic luminous efficacy of radiation: as above with the CIE 1951 V'(λ) (SpectralLibrary::
/// scotopic_v_prime()) and K'_m = 1700 lm/W. The result is in scotopic lm/W.
LuminousEfficacy scotopic_luminous_efficacy_lm_W(const Spectrum& spectrum, const TabulatedSpectrum& v_prime,
                                                 IntegrationGrid grid = IntegrationGrid::cie_1nm());

/// Melanopic daylight (D65) efficacy ratio of `spectrum`'s shape (CIE S 026/E:2018, "melanopic DER"): its melanopic
/// efficacy of luminous radiation Σ S s_mel Δλ / (K_m Σ S V Δλ) in W/lm over D65's, K_mel,v^D65 = 1.3262 mW/lm.
/// Melanopic EDI = DER × illuminance (lx). `s_mel` is SpectralLibrary::melanopic_action_spectrum(). Throws
/// InputError as luminous_efficacy_of_radiation_lm_W does.
double melanopic_daylight_efficacy_ratio(const Spectrum& spectrum, const TabulatedSpectrum& v,
                                         const TabulatedSpectrum& s_mel, IntegrationGrid grid = IntegrationGrid::cie_1nm());

/// Φv = K Φe, for a source whose spectral shape has efficacy `k`.
constexpr LuminousPower to_luminous(RadiantPower p, LuminousEfficacy k) { return LuminousPower(p.w * k.lm_W); }
/// Φe = Φv / K. `k` must be positive (as every efficacy computed above is).
constexpr RadiantPower to_radiant(LuminousPower p, LuminousEfficacy k) { return RadiantPower(p.lm / k.lm_W); }
/// Iv = K Ie.
constexpr LuminousIntensity to_luminous(RadiantIntensity i, LuminousEfficacy k) {
  return LuminousIntensity(i.w_sr * k.lm_W);
}
/// Ie = Iv / K.
constexpr RadiantIntensity to_radiant(LuminousIntensity i, LuminousEfficacy k) {
  return RadiantIntensity(i.cd / k.lm_W);
}
/// Ev = K Ee.
constexpr Illuminance to_luminous(Irradiance e, LuminousEfficacy k) { return Illuminance(e.w_m2 * k.lm_W); }
/// Ee = Ev / K.
constexpr Irradiance to_radiant(Illuminance e, LuminousEfficacy k) { return Irradiance(e.lx / k.lm_W); }
/// Lv = K Le.
constexpr Luminance to_luminous(Radiance l, LuminousEfficacy k) { return Luminance(l.w_m2_sr * k.lm_W); }
/// Le = Lv / K.
constexpr Radiance to_radiant(Luminance l, LuminousEfficacy k) { return Radiance(l.nt / k.lm_W); }

}  // namespace rimu
