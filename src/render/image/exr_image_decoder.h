// OpenEXR image textures and environment maps decoded with OpenEXR itself, which Rimu links for its film output:
// an HDR environment map, the lighter's usual light, then never loads the OpenImageIO module (~120 MiB resident,
// ~0.25 s of CPU once per process; image_library.h). The file is taken only where the result is what OpenImageIO
// gives (the same DecodedImage fields and the same floats, bit for bit: tests/render/exr_image_decoder_test.cpp):
// a flat (not deep) first part whose channels are exactly R, G, B with or without A, or Y with or without A, each
// of type half or float and sampled at every pixel. Anything else (layers such as `diffuse.R`, luminance-chroma,
// 32-bit integer channels, subsampled channels, extra channels such as Z) goes to OpenImageIO, which orders and
// converts such channels in its own way.
#pragma once

#include <filesystem>
#include <optional>

#include "render/image/image_module/image_module_api.h"

namespace rimu {

/// The header of `path` as OpenImageIO's read_header fills it (the data window's size, channels in the order R, G,
/// B, A or Y, A, alpha_channel, bits_per_sample 16 if every channel is half else 32, stored_as_float, format_name
/// "openexr"), if `path` is an OpenEXR file this decoder takes; nullopt for any other file. Opens the file through
/// open_exr_input (its header checks); throws InputError naming the file if OpenEXR cannot read the header.
std::optional<DecodedImage> exr_image_header(const std::filesystem::path& path);

/// The pixels of `path` as floats (the data window, row 0 at the top), `header` being what exr_image_header gave;
/// with `halves_if_half`, a file whose channels are all half fills DecodedImage::halves instead (half the memory,
/// the same values). Throws InputError naming the file if the file ends before its pixels do or OpenEXR cannot
/// decode them.
DecodedImage exr_image_pixels(const std::filesystem::path& path, const DecodedImage& header,
                              bool halves_if_half = false);

}  // namespace rimu
