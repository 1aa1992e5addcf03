// Colorimetry of a reflectance (or transmittance) factor under a CIE illuminant: the library side of
// `rimu-colour reflectance`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "spectral/colorimetry/cielab.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/spectrum_values_check.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "spectral/colorimetry/tristimulus_method.h"

namespace rimu {

/// Reads one column of a CSV (first column wavelength_nm; `column` empty = the second column) as a reflectance
/// factor, held at its end values beyond the data (CIE 15:2004 §7.2.2.1). Throws InputError with file:line for
/// a value outside 0-1.5 (check_reflectance_factors) and for everything CsvTable / TabulatedSpectrum refuse.
TabulatedSpectrum load_reflectance_csv(const std::filesystem::path& path, const std::string& column);

/// A ColorChecker Classic patch (BabelColor average, 10 nm) by its name with spaces ("dark skin",
/// "white 9.5 (.05 D)") or its column name ("dark_skin"). Throws InputError at `where` listing the 24 names.
TabulatedSpectrum colorchecker_patch(SpectralLibrary& library, const std::string& name, const SourceLocation& where = {});

struct ReflectanceConditions {
  std::string illuminant = "D50";
  StandardObserver observer = StandardObserver::cie1931_2deg;
  std::optional<TristimulusMethod> method;  ///< empty: default_tristimulus_method() of the sample
  /// For astm-e308: Table 6 if the data were corrected for the instrument's bandpass (the default), Table 5 if not.
  E308Table e308_table = E308Table::table6_bandpass_corrected;
};

/// One sample's colour under the conditions; XYZ and the white with the perfect diffuser at Y = 100.
struct ReflectanceColour {
  std::string description;
  std::string method;  ///< the tristimulus method used
  std::optional<E308Table> e308_table;  ///< the E308 table used, when the method is astm-e308
  Xyz xyz;
  Chromaticity xy;
  Xyz white;           ///< the illuminant's perfect reflecting diffuser, by the same method (CIELAB's white)
  Lab lab;
  Rgb srgb_encoded;    ///< Bradford-adapted from the illuminant's white to D65, sRGB curve, clipped to [0, 1]
  bool srgb_in_gamut = true;  ///< false if the linear sRGB had a component outside [0, 1] before clipping
};

struct ReflectanceReport {
  std::string illuminant, observer;
  ReflectanceColour sample;
  std::optional<ReflectanceColour> reference;
  double delta_e_1976 = 0, delta_e_2000 = 0;  ///< sample against reference, when there is one
};

ReflectanceColour measure_reflectance(const TabulatedSpectrum& sample, const ReflectanceConditions& conditions,
                                      SpectralLibrary& library);
/// The sample, and when `reference` is given, the reference and their ΔE*ab and ΔE00.
ReflectanceReport analyse_reflectance(const TabulatedSpectrum& sample, const TabulatedSpectrum* reference,
                                      const ReflectanceConditions& conditions, SpectralLibrary& library);

std::string reflectance_report_text(const ReflectanceReport& report);
std::string reflectance_report_json(const ReflectanceReport& report);

}  // namespace rimu
