// Linear RGB images read through OpenImageIO: the pixels behind image textures and environment maps.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Imath/half.h>

#include "spectral/colour_spaces/rgb_colour_space.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// How an image file's numbers are to be read.
struct ImageEncoding {
  /// The RGB colour space of the pixels (primaries and white): an RgbColourSpace name.
  std::string space = "srgb-linear";
  /// True if the values are sRGB-encoded (IEC 61966-2-1 curve) and must be decoded to linear first.
  bool srgb_transfer = false;
};

/// The encoding a file most likely has: 8/16-bit integer formats are sRGB-encoded sRGB, float formats linear sRGB.
ImageEncoding default_encoding_for(const std::filesystem::path& path);

/// A linear RGB image, row 0 at the top. Grey images are expanded to RGB; alpha and other channels are dropped,
/// and colour is kept as the file stores it (a PNG's colour is not multiplied by its alpha).
/// Pixels are held as floats, or, for a file of 8-bit samples, as its bytes (3 per pixel instead of 12), decoded
/// by pixel() through a 256-entry table (the sRGB curve or code/255): the same floats, bit for bit, as decoding
/// the file to floats first; or, for an OpenEXR file of half samples (most environment maps), as its halves (6 bytes
/// per pixel instead of 12), converted by pixel(): exactly the floats, as every half is a float. Half the bytes is
/// half the cache a sky's random reads sweep: a 2048² sky is 24 MiB instead of 48 (docs/benchmarks.md, "cloud,
/// fifth round").
class RgbImage {
 public:
  /// Reads `path` and decodes it to linear RGB. Throws InputError (file and the library's message) on failure, and
  /// for pixels that are NaN or infinite.
  static RgbImage read(const std::filesystem::path& path, const ImageEncoding& encoding);
  RgbImage(int width, int height, std::vector<float> rgb) : width_(width), height_(height), rgb_(std::move(rgb)) {}
  /// IEEE 754 binary16 bit patterns, three per pixel, linear, all finite.
  RgbImage(int width, int height, std::vector<std::uint16_t> rgb16) : width_(width), height_(height), rgb16_(std::move(rgb16)) {}
  /// 8-bit codes, three per pixel, sRGB-encoded if `srgb_transfer`, else linear (code/255).
  RgbImage(int width, int height, std::vector<std::uint8_t> rgb8, bool srgb_transfer)
      : width_(width), height_(height), rgb8_(std::move(rgb8)), decode_(decode_table(srgb_transfer)) {}

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb pixel(int x, int y) const {
    const size_t i = 3 * (size_t(y) * size_t(width_) + size_t(x));
    if (decode_) return {decode_[rgb8_[i]], decode_[rgb8_[i + 1]], decode_[rgb8_[i + 2]]};
    if (!rgb16_.empty()) {
      const std::uint16_t* h = &rgb16_[i];
      return {imath_half_to_float(h[0]), imath_half_to_float(h[1]), imath_half_to_float(h[2])};
    }
    const float* p = &rgb_[i];
    return {p[0], p[1], p[2]};
  }
  /// True if the pixels are 8-bit codes: then bytes() holds them and decode_table() their linear values.
  bool is_8bit() const { return decode_ != nullptr; }
  const std::vector<std::uint8_t>& bytes() const { return rgb8_; }
  const float* decode_table() const { return decode_; }
  /// Bilinear lookup at texture coordinates (u, v) ∈ [0,1)², repeating outside; v = 0 is the BOTTOM row
  /// (the OBJ/OpenGL convention), so v is flipped against the image's rows.
  Rgb bilinear(Vec2 uv) const;

  /// The linear value of each 8-bit code: srgb_decode(code/255) (IEC 61966-2-1) or code/255, as floats.
  static const float* decode_table(bool srgb_transfer);

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> rgb_;
  std::vector<std::uint8_t> rgb8_;
  std::vector<std::uint16_t> rgb16_;
  const float* decode_ = nullptr;  // a static table (decode_table) when the pixels are 8-bit codes
};

}  // namespace rimu
