// Everything a colour scientist asks of a light's spectrum, in one report (the library side of `rimu-colour report`).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "spectral/colorimetry/astm_e308.h"
#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colour_rendering/colour_rendering_index.h"
#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/library/spectrum_source.h"
#include "spectral/colorimetry/tristimulus_method.h"

namespace rimu {

/// The colorimetry and photometry of one emission spectrum.
struct SpectrumReport {
  std::string description;
  /// How XYZ was summed: "native" (the table's own 1 or 5 nm wavelengths, CIE 15:2004 §7.1), "astm-e308"
  /// (10/20 nm data) or "1nm" (interpolated to 1 nm; also every continuous spectrum: blackbody, daylight).
  std::string tristimulus_method;
  std::optional<E308Table> e308_table;  ///< the E308 table used, when tristimulus_method is astm-e308
  Xyz xyz_2deg;        ///< relative, Y = 100 (CIE 1931 2°), by tristimulus_method
  Chromaticity xy_2deg;
  Uv1976 uv_prime_2deg;
  Xyz xyz_10deg;       ///< relative, Y = 100 (CIE 1964 10°)
  Chromaticity xy_10deg;
  Xyz absolute_xyz;    ///< K_m ∫ S x̄ dλ ...: cd/m² if S is a spectral radiance in W/(m²·sr·nm) (native sum for
                       ///< native data, else 1 nm)
  CctDuv cct;          ///< CCT and Duv (Ohno 2013), 2° observer
  double luminous_efficacy_lm_w = 0;           ///< of radiation, photopic, 360-830 nm
  double scotopic_luminous_efficacy_lm_w = 0;  ///< of radiation, scotopic (K'_m = 1700 lm/W)
  std::optional<ColourRenderingIndex> cri;     ///< empty when CIE 13.3 defines none (CCT outside 1000-25000 K)
  std::string cri_unavailable_reason;
  Rgb srgb_linear;     ///< the light's colour at Y = 1 in linear sRGB (no chromatic adaptation)
  Rgb acescg;          ///< the same in ACEScg
};

/// Builds the spectrum described by `source` and analyses it. `method` overrides the tristimulus method chosen
/// from the data's spacing (default_tristimulus_method()); `e308_table` picks E308's Table 6 (data corrected for
/// bandpass) or Table 5 (uncorrected) when that method is astm-e308. Throws InputError for bad input.
SpectrumReport analyse_spectrum(const SpectrumSource& source, SpectralLibrary& library,
                                std::optional<TristimulusMethod> method = std::nullopt,
                                E308Table e308_table = E308Table::table6_bandpass_corrected);
/// Analyses an existing spectrum. Continuous spectra (not tables) are always summed at 1 nm; asking for another
/// method for them is an InputError.
SpectrumReport analyse_spectrum(const Spectrum& spectrum, const std::string& description, SpectralLibrary& library,
                                std::optional<TristimulusMethod> method = std::nullopt,
                                E308Table e308_table = E308Table::table6_bandpass_corrected);

/// A human-readable report (several lines, ending with a newline).
std::string report_text(const SpectrumReport& report);
/// The same as JSON (one object, pretty-printed, ending with a newline).
std::string report_json(const SpectrumReport& report);

}  // namespace rimu
