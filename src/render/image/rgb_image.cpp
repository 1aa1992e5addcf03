#include "render/image/rgb_image.h"

#include <array>
#include <cmath>
#include <optional>

#include "render/image/image_file.h"
#include "render/image/exr_header_check.h"
#include "render/image/exr_image_decoder.h"
#include "render/image/image_library.h"
#include "render/image/stb_image_decoder.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {

ImageEncoding default_encoding_for(const std::filesystem::path& path) {
  const std::uintmax_t file_bytes = check_input_file(path, kMaxBinaryFileBytes);  // OpenImageIO would block on a FIFO
  // OpenEXR allocates header attributes at their claimed size inside the library (exr_header_check.h).
  check_exr_header_sizes(path, file_bytes);
  ImageEncoding encoding;
  // Only the header is needed: as stored, so that stb_image takes a file with alpha too.
  if (const std::optional<DecodedImage> stb = stb_image_header(path, true)) {
    encoding.srgb_transfer = !stb->stored_as_float;
    return encoding;
  }
  if (exr_image_header(path)) return encoding;  // float: linear
  DecodedImage header;
  if (std::string error; !image_reader_for(path).read_header(path.string(), header, error)) return encoding;
  encoding.srgb_transfer = !header.stored_as_float;
  return encoding;
}

const float* RgbImage::decode_table(bool srgb_transfer) {
  // The float OpenImageIO gives for a code (code/255 as a float), then decoded as RgbImage::read decodes floats.
  struct Tables {
    std::array<float, 256> linear{}, srgb{};
    Tables() {
      for (int code = 0; code < 256; ++code) {
        const float v = float(code) / 255.0f;
        linear[size_t(code)] = v;
        srgb[size_t(code)] = float(srgb_decode(v));
      }
    }
  };
  static const Tables tables;  // a pure function's cache, filled on first use
  return srgb_transfer ? tables.srgb.data() : tables.linear.data();
}

namespace {

// Pixel i's R, G, B (grey repeated; alpha and further channels dropped) at [3i, 3i + 3), each sample passed through
// decode(sample, i). Three or more channels are compacted in place: pixel i's RGB never lands past where its
// channels were, so one forward pass reads every sample before it is overwritten. That saves a copy of the image
// (48 MiB for a 2048² sky of floats) and its first touch of fresh pages: the copy and its zero-fill were a third of
// the load of the pbrt-v3 cloud scene (docs/benchmarks.md, "pbrt-v3 scenes"). Grey needs a new buffer.
template <typename Sample, typename Decode>
std::vector<Sample> rgb_of(std::vector<Sample>&& raw, int channels, size_t count, Decode decode) {
  const bool in_place = channels >= 3;
  std::vector<Sample> grey_to_rgb;
  if (!in_place) grey_to_rgb.resize(count * 3);
  std::vector<Sample>& rgb = in_place ? raw : grey_to_rgb;
  for (size_t i = 0; i < count; ++i) {
    Sample v[3];
    for (int c = 0; c < 3; ++c) v[c] = decode(raw[i * size_t(channels) + size_t(channels >= 3 ? c : 0)], i);
    for (int c = 0; c < 3; ++c) rgb[3 * i + size_t(c)] = v[c];
  }
  rgb.resize(count * 3);
  if (channels > 3) rgb.shrink_to_fit();  // an alpha channel's quarter is not kept
  return std::move(rgb);
}

}  // namespace

RgbImage RgbImage::read(const std::filesystem::path& path, const ImageEncoding& encoding) {
  // Colour as stored, not multiplied by alpha: a texture's colour is a reflectance, and a cut-out applies its alpha
  // separately (stochastically, as pbrt-v4 does), so premultiplied texels would darken the edges of a leaf twice.
  // pbrt-v4 reads PNG and TGA colour unassociated too. (It also keeps stb_image's in-process path open to such files.)
  DecodedImage image = read_image_file(path, true, true);
  const int w = image.width, channels = image.channels, h = image.height;
  const size_t count = size_t(w) * size_t(h);
  if (!image.bytes.empty()) {
    // 8-bit codes kept as they are (every code is finite): RGB as read, or grey repeated, or RGB without alpha.
    if (channels == 3) return RgbImage(w, h, std::move(image.bytes), encoding.srgb_transfer);
    std::vector<std::uint8_t> rgb8 = rgb_of(std::move(image.bytes), channels, count, [](std::uint8_t v, size_t) { return v; });
    return RgbImage(w, h, std::move(rgb8), encoding.srgb_transfer);
  }
  const auto refuse = [&](size_t i) {
    throw InputError({path.string(), 0, ""}, "pixel (" + std::to_string(i % size_t(w)) + ", " +
                                                 std::to_string(i / size_t(w)) + ") is not a finite number");
  };
  if (!image.halves.empty() && !encoding.srgb_transfer) {
    // Halves (an OpenEXR file of half samples) kept as halves: the same values in half the bytes.
    std::vector<std::uint16_t> rgb16 = rgb_of(std::move(image.halves), channels, count, [&](std::uint16_t v, size_t i) {
      if ((v & 0x7c00u) == 0x7c00u) refuse(i);  // the exponent of infinities and NaNs
      return v;
    });
    return RgbImage(w, h, std::move(rgb16));
  }
  if (!image.halves.empty()) {
    // sRGB-encoded halves (an unusual file): decoded below as floats.
    image.pixels.resize(image.halves.size());
    for (size_t i = 0; i < image.halves.size(); ++i) image.pixels[i] = imath_half_to_float(image.halves[i]);
    image.halves = {};
  }
  std::vector<float> rgb = rgb_of(std::move(image.pixels), channels, count, [&](float v, size_t i) {
    if (!std::isfinite(v)) refuse(i);
    return encoding.srgb_transfer ? float(srgb_decode(v)) : v;
  });
  return RgbImage(w, h, std::move(rgb));
}

Rgb RgbImage::bilinear(Vec2 uv) const {
  // Texel centres at (i + 0.5)/width; repeat wrapping.
  const float x = (uv.x - std::floor(uv.x)) * float(width_) - 0.5f;
  const float y = (1.0f - (uv.y - std::floor(uv.y))) * float(height_) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  const int x0 = wrap(int(fx), width_), x1 = wrap(int(fx) + 1, width_);
  const int y0 = wrap(int(fy), height_), y1 = wrap(int(fy) + 1, height_);
  const Rgb a = pixel(x0, y0), b = pixel(x1, y0), c = pixel(x0, y1), d = pixel(x1, y1);
  auto mix = [&](double pa, double pb, double pc, double pd) {
    return (1 - ty) * ((1 - tx) * pa + tx * pb) + ty * ((1 - tx) * pc + tx * pd);
  };
  return {mix(a.r, b.r, c.r, d.r), mix(a.g, b.g, c.g, d.g), mix(a.b, b.b, c.b, d.b)};
}

}  // namespace rimu
