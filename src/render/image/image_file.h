// Reading an image file's pixels, with its header checked first: the one way image textures, environment maps,
// normal maps and alpha masks are read (RgbImage::read, AlphaMask::read). PNG, JPEG, TGA and BMP are
// decoded in-process by stb_image (stb_image_decoder.h), OpenEXR files of R, G, B (A) or Y (A) by OpenEXR
// (exr_image_decoder.h); every other file by the OpenImageIO module.
//
// An image header states the size of what follows, and the decoder allocates that much before it finds the file
// short: a 69-byte PNG claiming 65535 × 65535 pixels would allocate 51 GB. So the header's size is checked against
// the file's size and against a fixed limit before any pixel is decoded (docs/scene-format.md, "Limits").
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "render/image/image_module/image_module_api.h"

namespace rimu {

/// The most pixels an image may have: 2^27 = 134,217,728 (16384 × 8192, the largest common environment map).
/// An environment map costs about 40 bytes per texel while loading (docs/scene-format.md, "Limits"), so this bounds
/// one image at about 5 GB; a reflectance texture far less.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 27;

/// A compressed image holds at most this many pixels per byte of file. Deflate (PNG, EXR ZIP, TIFF) expands at
/// most 1032:1, so a 1-bit image holds at most 8,256 pixels per byte; other codecs (RLE, LZW, JPEG, PIZ) expand
/// less. Twice deflate's bound leaves room for headers and rounding.
inline constexpr std::uint64_t kMaxPixelsPerFileByte = 16384;

/// Throws InputError naming `file` if `header` (as read_header fills it) describes an image that the file's
/// `file_bytes` cannot hold or that is larger than kMaxImagePixels: an empty size; more pixels than the limit;
/// an uncompressed format (PPM, PGM, PBM, PFM) whose pixel data is longer than the file; any other format claiming
/// more than kMaxPixelsPerFileByte pixels per byte of file.
void check_image_header(const DecodedImage& header, std::uintmax_t file_bytes, const std::string& file);

/// The pixels of `path` as floats (DecodedImage), or, if `compact`, as stored where that is smaller: bytes for a file
/// of 8-bit samples, halves for an OpenEXR file of half samples; after check_input_file and check_image_header.
/// `as_stored` as in DecodedImage. Loads OpenImageIO only for a file that stb_image_header leaves to it. Throws InputError naming the file for a file that is not a regular image file,
/// a header that fails the checks, or pixels the library cannot decode.
DecodedImage read_image_file(const std::filesystem::path& path, bool as_stored, bool compact = false);

/// An image's size in pixels.
struct ImageSize {
  int width = 0, height = 0;
};

/// The size `path`'s header states, after the checks of read_image_file, without decoding a pixel (for choosing how
/// to read an image before reading it). Throws InputError as read_image_file does.
ImageSize read_image_size(const std::filesystem::path& path);

}  // namespace rimu
