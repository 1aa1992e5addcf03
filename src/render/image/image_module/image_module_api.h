// The functions of Rimu's OpenImageIO module (librimu_oiio.so), shared by the module and its loader
// (render/image/image_library.cpp). The module is a separate shared object so that a render that reads no image texture
// and writes no PNG/JPEG/TIFF never loads OpenImageIO: Debian's OpenImageIO pulls in ~250 libraries (OpenCV,
// FFmpeg, GDAL, DCMTK …) whose relocation costs ≈ 0.25 s of CPU per process, which a farm pays once per task.
// Both sides are built by the same build with the same compiler and standard library, so std::string and
// std::vector cross the boundary; exceptions do not: every function returns false and fills `error` instead.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rimu {

/// Bumped whenever a signature below changes, so that a stale module is refused rather than called wrongly.
inline constexpr int kImageModuleApiVersion = 5;

/// The pixels of an image file, interleaved, row 0 at the top: as 32-bit floats, or as the file's own bytes for a
/// file of 8-bit samples if the caller asks (four times less memory than floats, and no conversion buffer).
struct DecodedImage {
  int width = 0, height = 0, channels = 0;
  bool stored_as_float = false;  ///< the file holds float/half/double values (not 8/16-bit integer codes)
  int alpha_channel = -1;        ///< the index of the alpha channel, -1 if the file has none
  int bits_per_sample = 0;       ///< bits one channel of one pixel takes in the file (1 for a bitmap, 32 for float)
  std::string format_name;       ///< OpenImageIO's name of the file's format: "png", "openexr", "pnm" (PPM/PFM) …
  /// Set by the caller before read_pixels: keep colour channels as stored instead of letting OpenImageIO multiply
  /// them by alpha (a mask read from the red channel must not gain the alpha channel's holes).
  bool as_stored = false;
  /// Set by the caller before read_pixels: a file of 8-bit samples fills `bytes` (the codes as stored) and leaves
  /// `pixels` empty; any other file fills `pixels`.
  bool bytes_if_8bit = false;
  std::vector<float> pixels;
  std::vector<std::uint8_t> bytes;
  /// An OpenEXR file of half samples read as stored (exr_image_pixels with halves_if_half; never by the module):
  /// the IEEE 754 binary16 bit patterns, and `pixels` empty.
  std::vector<std::uint16_t> halves;
};

struct ImageModuleApi {
  int api_version;
  /// True if this OpenImageIO build has a writer for `format` ("png", "jpeg", "tiff").
  bool (*can_write)(const std::string& format, std::string& error);
  /// Writes 8-bit RGB pixels (width·height·3, row 0 at the top) to `path` as `format`, with the attributes
  /// Software, rimu:view and, if `srgb_encoded`, oiio:ColorSpace = sRGB.
  bool (*write_rgb8)(const std::string& path, const std::string& format, int width, int height,
                     const std::vector<uint8_t>& pixels, const std::string& software, const std::string& view,
                     bool srgb_encoded, std::string& error);
  /// Reads only the header of `path`: sets `image`'s size, channels and stored_as_float (pixels left empty).
  bool (*read_header)(const std::string& path, DecodedImage& image, std::string& error);
  /// Reads the whole first subimage of `path`: as floats, or as bytes (DecodedImage::bytes_if_8bit).
  bool (*read_pixels)(const std::string& path, DecodedImage& image, std::string& error);
};

}  // namespace rimu

/// The one symbol the module exports.
extern "C" const rimu::ImageModuleApi* rimu_image_module_api();
