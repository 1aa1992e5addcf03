// A human-readable report of one upsampled colour: what `rimu-colour upsample` prints.
#pragma once

#include <filesystem>
#include <memory>
#include <ostream>
#include <vector>

#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/upsampling/rgb_upsampler.h"

namespace rimu {

/// How to write the report.
struct UpsampleReportOptions {
  bool emission = false;               ///< upsample as a light (no ≤ 1 limit) instead of a reflectance
  bool csv = false;                    ///< the spectrum as "wavelength_nm,value" CSV only
  std::filesystem::path plot_png;      ///< if set, also plot the spectrum there (gnuplot_process.h)
};

/// The largest magnitude of an RGB component write_upsample_report() accepts.
inline constexpr double kMaxUpsampleComponent = kMaxColourComponent;

/// One upsampled colour, with what the report prints about it.
struct UpsampledColour {
  std::shared_ptr<const Spectrum> spectrum;  ///< the ReflectanceSpectrum or EmissionSpectrum
  std::vector<double> knot_values;           ///< the spectrum at every knot (upsample_knot_nm)
  Rgb round_trip;                            ///< the spectrum's RGB under the space's white (emission: at the input Y)
  bool gamut_mapped = false;
  double delta_e2000 = 0;                    ///< between the input and the round trip
};

/// Upsamples `rgb` as a reflectance or (emission) a light, the way every front end does (`rimu-colour upsample`,
/// the Python module). Throws InputError at `where` for a component outside ±kMaxUpsampleComponent or NaN
/// (check_colour_components), and for a result that is not finite.
UpsampledColour upsample_colour(const RgbUpsampler& upsampler, const Rgb& rgb, bool emission,
                                const SourceLocation& where);

/// Upsamples `rgb` (upsample_colour at "rgb") and writes the spectrum at every 5 nm knot, the round-trip RGB (under
/// the space's white), the CIEDE2000 distance and whether gamut mapping acted. Throws InputError as upsample_colour
/// does, or for a plot path that cannot be written (checked before anything is printed); PlotError if gnuplot is
/// missing or fails.
void write_upsample_report(std::ostream& out, const RgbUpsampler& upsampler, const Rgb& rgb,
                           const UpsampleReportOptions& options = {});

}  // namespace rimu
