// Colorimetry of measured (tabulated) spectra by the method their sampling calls for: the toolkit's measurement
// path. The renderer keeps its own continuous-spectrum path (colorimetry.h, sampled wavelengths).
#pragma once

#include <string_view>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "spectral/colorimetry/tristimulus_method.h"

namespace rimu {

/// The CMFs' range: native sums use the data's wavelengths inside it (CIE 15:2004 §7.1).
inline constexpr double kCmfFirst_nm = 360.0;
inline constexpr double kCmfLast_nm = 830.0;

/// Relative XYZ (Y = 100) of a light's spectral power table.
///   native    Σ S(λi) x̄(λi) over the table's own wavelengths (evenly spaced data only)
///   1nm       the table interpolated linearly to 1 nm over 360-830 nm (zero outside its range)
///   astm-e308 the E308 weights of the equal-energy illuminant E for the table's spacing (`e308_table`: Table 6
///             for data corrected for bandpass, Table 5 for uncorrected data; ignored by the other methods)
/// Throws InputError when the method does not fit the data (uneven spacing for native; E308 rules).
Xyz light_xyz(const TabulatedSpectrum& light, StandardObserver observer, TristimulusMethod method,
              SpectralLibrary& library, E308Table e308_table = E308Table::table6_bandpass_corrected);

/// Relative XYZ of a reflectance (or transmittance) factor under a named CIE illuminant, white = the perfect
/// diffuser with Y = 100 (CIE 15:2004 eq. 7.2):
///   native    k Σ R S x̄ at the data's wavelengths, k = 100 / Σ S ȳ at the same wavelengths
///   1nm       the factor interpolated to 1 nm (end values held beyond the data, §7.2.2.1), summed with the
///             illuminant's table over 360-830 nm
///   astm-e308 Σ R_j W_j with the E308 weights of that illuminant, observer and spacing (data/e308/), from
///             `e308_table` (Table 6 for bandpass-corrected data, Table 5 for uncorrected data)
Xyz reflectance_xyz(const TabulatedSpectrum& reflectance, std::string_view illuminant, StandardObserver observer,
                    TristimulusMethod method, SpectralLibrary& library,
                    E308Table e308_table = E308Table::table6_bandpass_corrected);

/// XYZ of the perfect reflecting diffuser under the illuminant by the same method and at the same wavelengths as
/// `reflectance` (the white CIELAB needs for it).
Xyz perfect_diffuser_xyz(const TabulatedSpectrum& reflectance, std::string_view illuminant,
                         StandardObserver observer, TristimulusMethod method, SpectralLibrary& library,
                         E308Table e308_table = E308Table::table6_bandpass_corrected);

}  // namespace rimu
