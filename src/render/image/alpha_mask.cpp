#include "render/image/alpha_mask.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "render/image/image_file.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/error.h"

namespace rimu {

AlphaMask AlphaMask::constant(float alpha) {
  AlphaMask mask;
  mask.constant_ = std::clamp(alpha, 0.0f, 1.0f);
  return mask;
}

AlphaMask AlphaMask::read(const std::filesystem::path& path, int channel, bool srgb, bool invert, bool clamp_to_unit) {
  const DecodedImage image = read_image_file(path, true);
  const int w = image.width, h = image.height, channels = image.channels;
  int source = channel;
  if (channel == 3) {
    source = image.alpha_channel;
    if (source < 0)
      throw InputError({path.string(), 0, ""}, "the image has no alpha channel (it has " + std::to_string(channels) +
                                                   " channels); choose \"channel\": \"r\", \"g\" or \"b\"");
  } else if (channels < 3) {
    source = 0;  // grey (or grey + alpha): every colour channel is the grey one
  }
  const std::vector<float>& raw = image.pixels;
  AlphaMask mask;
  mask.width_ = w;
  mask.height_ = h;
  mask.values_.resize(size_t(w) * size_t(h));
  for (size_t i = 0; i < mask.values_.size(); ++i) {
    float v = raw[i * size_t(channels) + size_t(source)];
    if (!std::isfinite(v))
      throw InputError({path.string(), 0, ""}, "pixel (" + std::to_string(i % size_t(w)) + ", " +
                                                   std::to_string(i / size_t(w)) + ") is not a finite number");
    // Alpha channels hold coverage linearly; only colour data carries the sRGB curve.
    if (srgb && channel != 3) v = float(srgb_decode(v));
    if (invert) v = 1.0f - v;
    mask.values_[i] = clamp_to_unit ? std::clamp(v, 0.0f, 1.0f) : v;
  }
  return mask;
}

float AlphaMask::evaluate(Vec2 uv) const {
  if (values_.empty()) return constant_;
  // Texel centres at (i + 0.5)/width, repeat wrapping, v flipped against the rows: the lookup RgbImage makes.
  const float x = (uv.x - std::floor(uv.x)) * float(width_) - 0.5f;
  const float y = (1.0f - (uv.y - std::floor(uv.y))) * float(height_) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  const int x0 = wrap(int(fx), width_), x1 = wrap(int(fx) + 1, width_);
  const int y0 = wrap(int(fy), height_), y1 = wrap(int(fy) + 1, height_);
  const auto at = [this](int px, int py) { return values_[size_t(py) * size_t(width_) + size_t(px)]; };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1));
}

bool alpha_keeps_hit(float alpha, Vec3 origin, Vec3 direction) {
  if (alpha >= 1.0f) return true;
  if (alpha <= 0.0f) return false;
  // A 64-bit mix of the six floats' bits (the SplitMix64 finaliser, Steele et al. 2014, per word), its top 24
  // bits a uniform number in [0, 1).
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (const float f : {origin.x, origin.y, origin.z, direction.x, direction.y, direction.z}) {
    h ^= std::bit_cast<uint32_t>(f) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    h ^= h >> 31;
  }
  const float u = float(h >> 40) * 0x1p-24f;
  return u < alpha;
}

}  // namespace rimu
