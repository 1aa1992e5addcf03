// The texels an image texture keeps: the source's own precision (8-bit codes of an 8-bit file, floats otherwise),
// decoded to linear RGB when a lookup reads them, and how their MIP levels are averaged.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace rimu {

/// A linear RGB texel in floats (12 bytes): the texels of a float or 16-bit image, and what 8-bit texels are
/// averaged in.
struct LinearRgbTexel {
  float r = 0, g = 0, b = 0;
};
inline void add_scaled(LinearRgbTexel& acc, const LinearRgbTexel& t, float w) {
  acc.r += w * t.r, acc.g += w * t.g, acc.b += w * t.b;
}

/// Three 8-bit codes as the file stores them (3 bytes); what they mean (the sRGB curve or code/255) is the codec's.
struct Rgb8Texel {
  std::array<std::uint8_t, 3> code{};
};

/// Decodes 8-bit texels through a 256-entry table of increasing linear values (RgbImage::decode_table) and stores an
/// average as the code whose value is nearest: a coarse level's texel is its region's linear mean to within half a
/// code step (for sRGB codes 0.5/255 of the encoded value: ≤ 0.2 % of a mid-grey's linear value, ≤ 0.7 % at code 10).
struct Rgb8Codec {
  using Linear = LinearRgbTexel;
  const float* table = nullptr;
  LinearRgbTexel decode(const Rgb8Texel& t) const { return {table[t.code[0]], table[t.code[1]], table[t.code[2]]}; }
  Rgb8Texel encode(const LinearRgbTexel& v) const { return {{nearest(v.r), nearest(v.g), nearest(v.b)}}; }
  std::uint8_t nearest(float v) const {
    const float* above = std::lower_bound(table, table + 256, v);
    if (above == table) return 0;
    if (above == table + 256) return 255;
    return std::uint8_t((v - above[-1] <= *above - v) ? above - 1 - table : above - table);
  }
};

}  // namespace rimu
