// The common texture formats decoded in-process with stb_image (Debian's libstb): PNG (8 and 16 bit), JPEG, TGA and
// BMP, formats pbrt-v4 reads with stb_image. Every other image goes to the OpenImageIO module
// (image_library.h), whose loading costs ~120 MiB of resident memory and ~0.25 s of CPU once per process: a scene
// whose images are all of these formats never pays it (docs/architecture.md, "Libraries loaded on demand").
//
// A file is taken only where stb_image gives what OpenImageIO gives: the same DecodedImage fields (format_name as
// OpenImageIO names the format, alpha_channel, bits_per_sample) and the same codes, scaled to floats as OpenImageIO
// scales them (code · (1/255), code · (1/65535)). JPEG is the exception: two IDCTs and upsamplers differ by a few
// codes (tests/render/stb_image_decoder_test.cpp states the bound). What is left to OpenImageIO, and why:
// - colour with alpha if a caller asks for it not as stored: OpenImageIO premultiplies a PNG's or TGA's colour by
//   its alpha (with the file's gamma), stb_image never does (Rimu's readers all read as stored);
// - TGA other than 8-bit grey or 24-bit colour without a colour map, or stored right to left (stb_image ignores
//   that flag and reads 16-bit colour without its alpha bit); BMP other than 24-bit uncompressed;
// - PNM: stb_image 2.27 reads 16-bit samples in the machine's byte order (wrong on x86) and leaves the codes of a
//   maximum other than 255 unscaled (OpenImageIO scales 15 to 255); telling those apart needs the header's maximum,
//   which stb_image does not report;
// - Radiance HDR: stb_image 2.27 loops for ever on a truncated run-length-encoded scanline (past the end it reads
//   zeros, and a run of length 0 never advances; found by mutating a 52-byte file), so a damaged .hdr would hang
//   the load instead of failing (HDR goes to the FreeImage module, image_library.h);
// - any file whose header stb_image refuses (12-bit or arithmetic-coded JPEG …): OpenImageIO may read it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "render/image/image_module/image_module_api.h"

namespace rimu {

/// The header of `path` as OpenImageIO's read_header fills it (size, channels, alpha_channel, bits_per_sample,
/// stored_as_float, format_name), if stb_image reads the file as OpenImageIO would when asked for its pixels
/// `as_stored` (DecodedImage::as_stored); nullopt if the file is for OpenImageIO. Reads only the file's header.
std::optional<DecodedImage> stb_image_header(const std::filesystem::path& path, bool as_stored);

/// The pixels of `path` decoded by stb_image, `header` being what stb_image_header gave: bytes for an 8-bit file if
/// `bytes_if_8bit`, floats otherwise (DecodedImage). Throws InputError naming the file if stb_image cannot decode
/// it, the file ends before its pixels do (stb_image itself reads zeros past the end of a TGA or BMP), or a PNG
/// chunk's CRC does not match (stb_image does not check it; libpng did).
DecodedImage stb_image_pixels(const std::filesystem::path& path, const DecodedImage& header, bool bytes_if_8bit);

}  // namespace rimu
