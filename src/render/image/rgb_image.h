// Linear RGB images read through OpenImageIO: the pixels behind image textures and environment maps.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

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

/// A linear RGB image, row 0 at the top. Grey images are expanded to RGB; alpha and other channels are dropped.
class RgbImage {
 public:
  /// Reads `path` and decodes it to linear RGB. Throws InputError (file and the library's message) on failure, and
  /// for pixels that are NaN or infinite.
  static RgbImage read(const std::filesystem::path& path, const ImageEncoding& encoding);
  RgbImage(int width, int height, std::vector<float> rgb) : width_(width), height_(height), rgb_(std::move(rgb)) {}

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb pixel(int x, int y) const {
    const float* p = &rgb_[3 * (size_t(y) * size_t(width_) + size_t(x))];
    return {p[0], p[1], p[2]};
  }
  /// Bilinear lookup at texture coordinates (u, v) ∈ [0,1)², repeating outside; v = 0 is the BOTTOM row
  /// (the OBJ/OpenGL convention), so v is flipped against the image's rows.
  Rgb bilinear(Vec2 uv) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> rgb_;
};

}  // namespace rimu
