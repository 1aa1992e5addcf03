// A rendered OpenEXR image as a film again, so `rimu display` can re-expose and re-view it without rendering: the
// display image comes from the same code, with the same decisions (metering, camera colour fit), as `rimu --png`.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>

#include "render/film/camera_colour_matrix.h"
#include "render/film/film.h"
#include "render/output/display_transform.h"
#include "render/output/exr_relight.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

/// A Rimu EXR read back for display.
struct ExrDisplaySource {
  std::unique_ptr<Film> film;                 ///< output_value() of every pixel is the image's written value
  std::optional<CameraColourFit> camera_fit;  ///< camera films: refitted from the camera named in the file
  bool white_balanced = false;                ///< the file records a white balance (rimu:whiteBalance)
  /// With white_balanced: the matrix the render applied to the written channels (rimu:whiteBalanceMatrix; for a
  /// file written before that attribute, rebuilt from rimu:whiteBalance by the render's own code; empty if that
  /// fails), which `--white-balance` undoes before adapting the white it is given.
  std::optional<Matrix3> white_balance_matrix;
  bool metered = false;                       ///< the render metered its display image (rimu:displayMetered)
  double nits_per_unit_y = 0;                 ///< luminance of the written Y = 1 (rimu:luminanceNitsPerUnitY)
};

/// Reads `path`: a partial render (rimu --samples/--checkpoint, a merge that kept its sums) through its exact sums
/// and record, so its film equals the one the render held; any other EXR Rimu wrote through its visible channels
/// (X, Y, Z of an XYZ film; R, G, B and rimu:camera of a camera film) and its light-group layers, as pixels of
/// weight 1 whose values are the file's. InputError naming the file if it cannot be read, is not an image Rimu wrote (no rimu:filmResponse), or
/// lacks the channels its film records.
ExrDisplaySource read_exr_for_display(const std::filesystem::path& path, SpectralLibrary& library);

/// `rimu display`: checks the display image's name (format by extension, not the input) and the view first, reads
/// `exr` and writes its display image to `display_image` as `rimu --png` would have (write_policy_display_image:
/// metered if the render was, or if `meter`, with `options.exposure_ev` as the compensation), logging to `log`.
/// `relight`: light groups rebalanced and a white balance applied first (render/output/exr_relight.h; a render's own
/// white balance undone first), so metering sees the relit image.
void write_exr_display_image(const std::filesystem::path& exr, const std::filesystem::path& display_image,
                             const DisplayOptions& options, bool meter, std::ostream& log,
                             const ExrRelightOptions& relight = {});

}  // namespace rimu
