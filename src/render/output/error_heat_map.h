// `rimu --noise-threshold T --preview-error heat.png`: where an adaptive render's noise still is, as a false-colour
// picture beside the preview, rewritten with it while rendering and once more at the end.
#pragma once

#include <filesystem>
#include <string>

#include "render/film/adaptive_sampling.h"
#include "render/output/false_colour_image.h"

namespace rimu {

/// Every pixel's relative standard error of luminance (AdaptiveSampling::relative_error, the 3×3 estimate the
/// stopping decision uses) in %, inside `bounds` (the film's crop window), row 0 at the top.
FalseColourValues adaptive_error_values(const AdaptiveSampling& adaptive, const PixelBounds& bounds);

/// The legend of every heat map of one render, fixed so that a colour means the same error in each preview: from a
/// tenth of the threshold (well converged) to 100 % (noise as large as the pixel), on a log scale. The threshold
/// itself sits a third of the way up for T = 1 %.
FalseColourRange adaptive_error_range(double noise_threshold);

/// Draws the heat map to `png` atomically (gnuplot, the false-colour palette), titled with the threshold and the
/// share of pixels still sampled.
void write_error_heat_map(const std::filesystem::path& png, const AdaptiveSampling& adaptive,
                          const PixelBounds& bounds);

}  // namespace rimu
