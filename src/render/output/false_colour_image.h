// `rimu display IN.exr --false-colour luminance|illuminance --png OUT.png`: a rendered EXR as a lighting designer's
// false-colour picture, each pixel coloured by its luminance in nt (cd/m²) — or by the illuminance a white
// Lambertian surface showing that luminance would receive, π·L in lx — on a log scale, with the legend beside it.
// Drawn by gnuplot with the palette of the sensors' plans (render/output/plot_output.h), so a colour means the same
// position on both legends.
//
// Units: the written Y of a pixel times the file's rimu:luminanceNitsPerUnitY (render/output/exr_display_source.h),
// the same scale `rimu display --meter` reads; a camera film's R, G, B go through its fitted camera-to-XYZ matrix.
// Illuminance: a rendered image holds luminance, not illuminance; E = π·L/ρ needs each surface's reflectance ρ,
// which the image does not have. "illuminance" shows E = π·L, exact for a white (ρ = 1) Lambertian surface and an
// underestimate by 1/ρ elsewhere; measured lux come from a sensor grid (the scene's "sensors").
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "render/output/exr_display_source.h"
#include "spectral/io/gnuplot_process.h"

namespace rimu {

enum class FalseColourQuantity {
  luminance,       ///< nt
  illuminance,     ///< lx, π × luminance
  relative_error,  ///< % of the pixel's luminance: an adaptive render's estimated standard error (error_heat_map.h)
};

/// "luminance" or "illuminance"; InputError naming `option` otherwise.
FalseColourQuantity parse_false_colour_quantity(const std::string& text, const std::string& option);

/// The legend's range, in the quantity's unit (nt or lx): low > 0, high > low.
struct FalseColourRange {
  double low = 1, high = 10000;
};
/// "LOW:HIGH", e.g. "1:10000"; InputError naming `option` unless both are finite, LOW > 0 and HIGH > LOW.
FalseColourRange parse_false_colour_range(const std::string& text, const std::string& option);

/// Per-pixel values of a false-colour image, row 0 at the top.
struct FalseColourValues {
  int width = 0, height = 0;
  std::vector<double> values;  ///< nt, lx or %; a pixel that is not a finite number is NaN (drawn as the bottom)
  FalseColourQuantity quantity = FalseColourQuantity::luminance;
};
/// The values of `source`'s pixels (its data window) in nt, or in lx as π × nt.
FalseColourValues false_colour_values(const ExrDisplaySource& source, FalseColourQuantity quantity);

/// The default legend: the 1st and 99th percentiles of the finite positive values, so a few specular highlights
/// or black pixels do not squeeze the scale; when those are equal (a uniform image) a decade either side. InputError
/// naming `option` when no pixel is positive (a black image has no log scale: give a range).
FalseColourRange default_false_colour_range(const std::vector<double>& values, const std::string& option);

/// Where `value` sits on the legend, log(value/low)/log(high/low), clamped to [0, 1]; 0 for NaN and values ≤ 0.
double false_colour_position(double value, const FalseColourRange& range);

/// The gnuplot job: the image (values clamped to the range, so every pixel has a colour) on a log colour scale with
/// the legend labelled in the unit, titled `title`.
GnuplotJob false_colour_job(const FalseColourValues& image, const FalseColourRange& range, const std::string& title);

/// `rimu display --false-colour`: checks `png` first (name, folder, not the input, gnuplot), reads `exr`, writes the
/// false-colour PNG atomically, and logs the range and the fractions of pixels below and above it to `log`.
void write_exr_false_colour(const std::filesystem::path& exr, const std::filesystem::path& png,
                            FalseColourQuantity quantity, const std::optional<FalseColourRange>& range,
                            std::ostream& log);

}  // namespace rimu
