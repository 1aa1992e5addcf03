// The display image: a film through the OpenColorIO view transform, written as an 8-bit PNG.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "render/display_transform.h"
#include "render/film.h"

namespace rimu {

/// The film's crop window as display-encoded 8-bit RGB, row by row from the top (exposure, view transform,
/// clamp to [0, 1], round to the nearest of 0…255). Throws InputError for a bad config or view.
std::vector<uint8_t> display_pixels(const Film& film, const DisplayOptions& options);

/// Writes display_pixels() as a PNG of the crop window's size through OpenImageIO, via a temporary file and a
/// rename (write_atomically). OpenImageIO's bool + geterror() failures become OutputError naming `path`; a
/// missing folder or a bad view is an InputError.
void write_display_png(const std::filesystem::path& path, const Film& film, const DisplayOptions& options = {});

}  // namespace rimu
