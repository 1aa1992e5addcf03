// The display image: a film through the OpenColorIO view transform, written as an 8-bit PNG (or JPEG or TIFF).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/output/display_transform.h"
#include "render/film/film.h"

namespace rimu {

/// The film's crop window as display-encoded 8-bit RGB, row by row from the top (camera films through
/// options.camera_to_xyz when set, exposure, view transform, clamp to [0, 1], round to the nearest of 0…255;
/// a NaN becomes 0 and ±Inf clamps, so no non-finite value reaches the image). Throws InputError for a bad config
/// or view.
std::vector<uint8_t> display_pixels(const Film& film, const DisplayOptions& options);

/// The mean luminance of the film's crop window as the display sees it: the written Y of an XYZ film (or of a camera
/// film through options.camera_to_xyz), before the display exposure. 0 for a camera film without a matrix.
double mean_display_luminance(const Film& film, const DisplayOptions& options);

/// How much of a display image is nearly black or clipped, to warn about an image nobody can use.
struct DisplayLevels {
  double black_fraction = 0;    ///< pixels whose three codes are all ≤ kNearlyBlackCode
  double clipped_fraction = 0;  ///< pixels with some channel at 255
  double mean_code = 0;         ///< mean code value over all pixels and channels, 0…255
};
/// 4/255 in the sRGB encoding is a linear 0.12 % of white: darker than an 18 % grey by 7 stops.
inline constexpr int kNearlyBlackCode = 4;
DisplayLevels display_levels(const std::vector<uint8_t>& rgb);

/// The OpenImageIO format a display image is written in, from the extension of `path` (case-insensitive):
/// "png" for .png, "jpeg" for .jpg/.jpeg, "tiff" for .tif/.tiff, all 8-bit sRGB-encoded. Throws InputError naming
/// `path` and `option` for any other extension (an .exr gets a pointer to -o) or if OpenImageIO lacks the writer.
std::string display_image_format(const std::filesystem::path& path, const std::string& option = "--png");

/// Writes display_pixels() as a PNG, JPEG or TIFF (display_image_format()) of the crop window's size through
/// OpenImageIO, via a temporary file and a rename (write_atomically). Unless the view is "Raw", the file is marked
/// "oiio:ColorSpace" = "sRGB", which OpenImageIO 2.4 writes as the PNG sRGB chunk (with gAMA; tested) and, for
/// JPEG, in its Exif block; its TIFF writer records nothing for it. OpenImageIO's bool + geterror() failures become
/// OutputError naming
/// `path`; a missing folder, an unknown extension or a bad view is an InputError. Returns the image's levels.
DisplayLevels write_display_image(const std::filesystem::path& path, const Film& film,
                                  const DisplayOptions& options = {});

}  // namespace rimu
