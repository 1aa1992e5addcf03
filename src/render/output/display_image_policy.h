// What `rimu` does to make its display image usable, beyond the view transform: a camera film is shown through its
// fitted camera-to-XYZ matrix, a photometric scene without a camera exposure is metered, and an image that came out
// nearly black or nearly all clipped is warned about. Each decision is stated in the log.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>

#include "render/film/camera_colour_matrix.h"
#include "render/output/display_output.h"

namespace rimu {

/// The display exposure that shows the film's mean display luminance (mean_display_luminance()) as 18 % grey, as a
/// reflected-light meter would (physical_camera.h), plus `compensation_ev`, clamped to ±kMaxDisplayExposure_ev.
/// Empty if the image has no light to meter (mean ≤ 0).
std::optional<double> metered_display_exposure_ev(const Film& film, const DisplayOptions& options,
                                                  double compensation_ev);

/// The decisions above for one job.
struct DisplayImagePolicy {
  std::optional<CameraColourFit> camera_fit;  ///< camera films: shown through it
  bool white_balanced = false;                ///< the written R, G, B include a white balance
  bool metered = false;                       ///< photometric scene, no camera exposure
  double nits_per_unit_y = 0;                 ///< of the displayed Y, for the log
  bool quiet = false;                         ///< log warnings only, not the notes on what was decided
};

/// A fraction of pixels at or above which an image is "nearly all" black or clipped.
inline constexpr double kNearlyAllPixels = 0.9;

/// Applies `policy` to `options` (the --exposure given there is the compensation), writes the display image with
/// write_display_image() and logs what was decided and any warning to `log`.
void write_policy_display_image(const std::filesystem::path& path, const Film& film, DisplayOptions options,
                                const DisplayImagePolicy& policy, std::ostream& log);

}  // namespace rimu
