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

}  // namespace rimu
