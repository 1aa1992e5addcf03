// Cut-outs: a shape's "alpha" (1 = the surface is there, 0 = a hole), as a constant or one channel of an image, and
// the rule a ray uses to decide whether it hits the surface or passes through.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "transport/geometry/vector.h"

namespace rimu {

/// A coverage value in [0, 1] over a surface's texture coordinates.
class AlphaMask {
 public:
  /// The same alpha everywhere (clamped to [0, 1]).
  static AlphaMask constant(float alpha);
  /// One channel of an image: `channel` 0-3 = R, G, B, A ("A" needs an alpha channel; a grey image has one
  /// channel, which every colour channel reads). `srgb_decode`: apply the sRGB curve first (8-bit colour data).
  /// `invert`: use 1 − value. `clamp_to_unit`: clamp each texel to [0, 1] (coverage); false keeps the values as read
  /// (a float texture's: an EXR roughness or displacement map may hold any finite value, pbrt-v4 keeps it; the
  /// parameter clamps at use where its range needs it). Throws InputError naming the file: unreadable, no such
  /// channel, a value not finite.
  static AlphaMask read(const std::filesystem::path& path, int channel, bool srgb_decode, bool invert,
                        bool clamp_to_unit = true);

  /// Alpha at (u, v): bilinear between texel centres, coordinates repeating, v = 0 the bottom row (as RgbImage);
  /// within [0, 1] when read clamped. Cost: four loads.
  float evaluate(Vec2 uv) const;

  /// The texels (row 0 at the top) and their size; a constant is one texel.
  int width() const { return values_.empty() ? 1 : width_; }
  int height() const { return values_.empty() ? 1 : height_; }
  std::vector<float> texels() const { return values_.empty() ? std::vector<float>{constant_} : values_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> values_;  // empty for a constant
  float constant_ = 1.0f;
};

/// Whether a ray from `origin` along `direction` meets a surface point of coverage `alpha`. Alpha 1 always, 0
/// never; a fractional alpha is kept with probability alpha, decided by a hash of the ray (as pbrt-v4 does), so
/// the same ray always gets the same answer — a camera ray and a shadow ray along one line agree — and a
/// half-transparent surface passes half the rays on average: stochastic transparency, unbiased for the average.
bool alpha_keeps_hit(float alpha, Vec3 origin, Vec3 direction);

}  // namespace rimu
