// 8-bit RGB PNG files written in-process with libpng: the display image of most renders (`--png`, `--preview`,
// `rimu display`). Writing them through the OpenImageIO module loaded its ~250 libraries (~120 MiB of resident
// memory and ~0.25 s of CPU) for one small file at the end of every render (docs/architecture.md, "Libraries loaded
// on demand"); JPEG and TIFF still go to it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace rimu {

/// What a display PNG says about itself: tEXt chunks (keyword, text; keywords of 1-79 Latin-1 characters), and
/// whether its codes are sRGB-encoded (then the sRGB chunk, rendering intent absolute colorimetric, with its gAMA
/// and cHRM fallbacks: what the OpenImageIO module wrote for the same image).
struct PngMetadata {
  std::vector<std::pair<std::string, std::string>> text;
  bool srgb_encoded = true;
};

/// Writes `pixels` (width·height·3 bytes, row 0 at the top) to `path` as an 8-bit RGB PNG. Throws RenderError
/// naming the file if libpng or the file system fails (the caller writes to a temporary name: output_file.h).
void write_png_rgb8(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& pixels,
                    const PngMetadata& metadata);

}  // namespace rimu
