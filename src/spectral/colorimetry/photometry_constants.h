// The constants that tie radiometry to photometry.
#pragma once

namespace rimu {

/// K_m, the maximum luminous efficacy for photopic vision, lm/W. The SI defines K_cd = 683 lm/W exactly at
/// 540 THz (555.016 nm in air); because V(λ) peaks at 555 nm rather than there, the CIE value of K_m for V(λ)
/// is 683.002 lm/W. Rimu uses 683 exactly, as CIE 15 and most renderers do; the difference is 3 ppm.
inline constexpr double kMaxLuminousEfficacy_lm_W = 683.0;
/// The CIE's more precise K_m (683.002 lm/W), kept for reference.
inline constexpr double kMaxLuminousEfficacyCie_lm_W = 683.002;
/// K'_m for scotopic vision with V'(λ) (CIE 1951), lm/W (1700.06 precisely; 1700 conventionally).
inline constexpr double kMaxScotopicLuminousEfficacy_lm_W = 1700.0;

/// K_mel,v^D65, the melanopic efficacy of luminous radiation of CIE standard illuminant D65 (CIE S 026/E:2018), in
/// W/lm (1.3262 mW/lm): melanopic irradiance ∫E(λ) s_mel(λ) dλ in W/m² divided by it is the melanopic equivalent
/// daylight (D65) illuminance in lx (the illuminance of D65 with the same melanopic effect).
inline constexpr double kMelanopicEfficacyD65_W_lm = 1.3262e-3;

}  // namespace rimu
