// How a tabulated spectrum is turned into tristimulus values: the measurement path of the colour toolkit.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rimu {

class TabulatedSpectrum;

/// The three summation practices a colour scientist meets (CIE 15:2004 §7, ASTM E308-15).
enum class TristimulusMethod {
  native,           ///< sum at the data's own wavelengths against the CMFs there (CIE 15:2004 §7.1, 1 and 5 nm data)
  interpolate_1nm,  ///< interpolate the data linearly to 1 nm over 360-830 nm, then sum (Rimu's former default)
  astm_e308,        ///< ASTM E308-15 weighting factors for 10 and 20 nm data: Table 6 (bandpass-corrected data) or Table 5 (uncorrected), by E308Table
};

/// "native", "1nm" or "astm-e308": the names used on the command line and in every report.
std::string_view method_name(TristimulusMethod method);
/// Parses those names; empty if the text is none of them.
std::optional<TristimulusMethod> parse_tristimulus_method(std::string_view text);

/// The constant spacing of a table in nm, or empty if its wavelengths are not evenly spaced (to 1e-6 nm).
std::optional<double> uniform_interval_nm(const TabulatedSpectrum& spectrum);

/// The method CIE 15 / ASTM E308 prescribe for data at this spacing: native for 1 and 5 nm (CIE 15:2004 §7.1:
/// the published tables were computed that way), astm-e308 for 10 and 20 nm (§7.2.2 points to weighting
/// factors, as too coarse a sum misses the CMFs' shape), 1 nm interpolation for anything else (irregular or odd
/// spacing, where no weights exist).
TristimulusMethod default_tristimulus_method(const TabulatedSpectrum& spectrum);

}  // namespace rimu
