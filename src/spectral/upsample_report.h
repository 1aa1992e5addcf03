// A human-readable report of one upsampled colour: what `rimu-colour upsample` prints.
#pragma once

#include <filesystem>
#include <ostream>

#include "spectral/rgb_upsampler.h"

namespace rimu {

/// How to write the report.
struct UpsampleReportOptions {
  bool emission = false;               ///< upsample as a light (no ≤ 1 limit) instead of a reflectance
  bool csv = false;                    ///< the spectrum as "wavelength_nm,value" CSV only
  std::filesystem::path plot_png;      ///< if set, also plot the spectrum there (gnuplot_process.h)
};

/// The largest magnitude of an RGB component write_upsample_report() accepts.
inline constexpr double kMaxUpsampleComponent = 1e30;

/// Upsamples `rgb` and writes the spectrum at every 5 nm knot, the round-trip RGB (under the space's white), the
/// CIEDE2000 distance and whether gamut mapping acted. Throws InputError for non-finite RGB or a plot path that
/// cannot be written (checked before anything is printed), PlotError if gnuplot is missing or fails.
/// CIEDE2000 distance and whether gamut mapping acted. Throws InputError (at "rgb") for a component outside
/// ±kMaxUpsampleComponent or NaN, or a result that is not finite; InputError for a failed plot.
void write_upsample_report(std::ostream& out, const RgbUpsampler& upsampler, const Rgb& rgb,
                           const UpsampleReportOptions& options = {});

}  // namespace rimu
