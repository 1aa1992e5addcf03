// MIP maps: an image texture's pyramid of ever coarser copies, and the filtered lookups that read it by the size of
// a ray's footprint (point, bilinear, trilinear, and EWA: Heckbert, "Fundamentals of Texture Mapping and Image
// Warping", 1989, as pbrt-v4 uses it).
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

#include "transport/geometry/vector.h"

namespace rimu {

/// How an image texture is filtered (pbrt-v4's imagemap "filter"). All but `point` blend texels bilinearly; the MIP
/// level follows the footprint for all of them (pbrt-v4's rule: `point` and `bilinear` read the finer of the two
/// levels around the footprint's width, `trilinear` blends the two, `ewa` weights an ellipse of texels on the two
/// levels around its minor axis and blends them). Without a footprint (after a diffuse bounce, or no differentials)
/// every filter reads the finest level.
enum class TextureFilter { point, bilinear, trilinear, ewa };

struct TextureFilterOptions {
  TextureFilter filter = TextureFilter::bilinear;  ///< pbrt-v4's default
  /// EWA only: the longest the ellipse's major axis may be, in multiples of its minor one (pbrt-v4's default 8).
  /// Longer ellipses are widened, trading blur across the footprint for a bounded texel count.
  float max_anisotropy = 8.0f;
};

/// acc += w·t for the values a pyramid averages.
inline void add_scaled(float& acc, float t, float w) { acc += w * t; }

/// How a pyramid's texels are averaged into a coarser level: `decode` gives the value averaged (`Linear`), `encode`
/// stores the average. This one averages texels as they are stored (floats, linear RGB floats); 8-bit texels
/// average in linear light and round back to their code (render/image/rgb_texels.h).
template <typename Texel>
struct StoredTexelCodec {
  using Linear = Texel;
  const Texel& decode(const Texel& t) const { return t; }
  Texel encode(const Linear& v) const { return v; }
};

/// The weight Heckbert's EWA gives a texel at squared elliptical radius r² ∈ [0, 1): a Gaussian exp(−α r²) − exp(−α)
/// with α = 2 (zero at the ellipse's edge), from a 128-entry table.
float ewa_gaussian_weight(float r2);

/// An image and its MIP levels. Level 0 is the image; level l + 1 halves each side of level l (rounding down, at
/// least 1) until both are 1 texel. A level is made from the one below by an area-weighted box filter: each new
/// texel averages exactly the region of the finer level it covers (2×2 texels for even sides, 2½ for odd ones), so
/// every level has the image's mean (up to float rounding) and the filter never reads across the image's edge:
/// the result does not depend on the wrap mode. Memory: Σ 4⁻ˡ ≤ 4/3 of the image's texels. Coordinates repeat
/// (Rimu's image textures tile); v = 0 is the image's bottom row.
template <typename Texel>
class MipPyramid {
 public:
  MipPyramid() = default;
  /// `base` holds width × height texels, row 0 at the top; `codec` says how texels are averaged (StoredTexelCodec).
  /// Cost: ⅓ of the image's texels, once, plus one level's rows of `Codec::Linear` while a level is made.
  template <typename Codec = StoredTexelCodec<Texel>>
  MipPyramid(int width, int height, std::vector<Texel> base, const Codec& codec = {}) {
    assert(width > 0 && height > 0 && base.size() == size_t(width) * size_t(height));
    levels_.push_back({width, height, std::move(base)});
    while (levels_.back().width > 1 || levels_.back().height > 1)
      levels_.push_back(downsampled(levels_.back(), codec));
  }

  int levels() const { return int(levels_.size()); }
  int width(int level) const { return levels_[size_t(level)].width; }
  int height(int level) const { return levels_[size_t(level)].height; }
  /// Texel (x, y) of a level, coordinates repeating.
  const Texel& texel(int level, int x, int y) const {
    const Level& l = levels_[size_t(level)];
    return l.texels[size_t(wrap(y, l.height)) * size_t(l.width) + size_t(wrap(x, l.width))];
  }
  /// Texels held over all levels (the base's count × ≤ 4/3).
  size_t texel_count() const {
    size_t n = 0;
    for (const Level& l : levels_) n += l.texels.size();
    return n;
  }

  /// The filtered value at texture coordinates `st` whose footprint is spanned by `dst_dx` = (∂s/∂x, ∂t/∂x) and
  /// `dst_dy`, handed out as weighted texels: `visit(const Texel* const texels[4], const float weights[4])` is
  /// called one or more times and all the weights sum to 1 (groups of four so that a caller can blend them the way
  /// it blends a bilinear lookup). Zero derivatives: a bilinear (point) lookup of level 0.
  template <typename Visit>
  void lookup(const TextureFilterOptions& options, Vec2 st, Vec2 dst_dx, Vec2 dst_dy, Visit&& visit) const {
    // Image coordinates a = s, b = 1 − t (down the rows) in [0, 1), and the footprint in level-0 texels.
    const float a = st.x - std::floor(st.x), b = 1.0f - (st.y - std::floor(st.y));
    const float w0 = float(width(0)), h0 = float(height(0));
    Vec2 ex{dst_dx.x * w0, -dst_dx.y * h0}, ey{dst_dy.x * w0, -dst_dy.y * h0};
    // A footprint that is not a number (a caller's overflow) is no footprint: never an undefined level index.
    // (An infinite one reads the coarsest level.)
    if (std::isnan(ex.x + ex.y + ey.x + ey.y)) ex = ey = Vec2{};
    const int top = levels() - 1;
    if (options.filter != TextureFilter::ewa) {
      // pbrt-v4's width: twice the largest derivative; the level where a texel is that wide.
      const float footprint = 2.0f * std::fmax(std::fmax(std::fabs(ex.x), std::fabs(ex.y)),
                                               std::fmax(std::fabs(ey.x), std::fabs(ey.y)));
      const float level = std::log2(std::fmax(footprint, 1e-8f));
      if (level >= float(top)) return visit_one(texel(top, 0, 0), visit);
      const int i = std::max(0, int(std::floor(level)));
      if (options.filter == TextureFilter::point) {
        const int x = int(std::lround(a * float(width(i)) - 0.5f)), y = int(std::lround(b * float(height(i)) - 0.5f));
        return visit_one(texel(i, x, y), visit);
      }
      if (options.filter == TextureFilter::bilinear || level <= 0.0f) return bilinear(i, a, b, 1.0f, visit);
      // Trilinear: blended continuously between the two levels around the footprint (pbrt-v4 reads level 0 alone
      // below level 1; blending from level 0 on avoids that jump in sharpness).
      const float t = level - float(i);
      bilinear(i, a, b, 1.0f - t, visit);
      bilinear(i + 1, a, b, t, visit);
      return;
    }
    // EWA: the major axis first; an ellipse more eccentric than max_anisotropy is widened along its minor axis.
    if (dot2(ex) < dot2(ey)) std::swap(ex, ey);
    const float major = std::sqrt(dot2(ex));
    float minor = std::sqrt(dot2(ey));
    if (minor * options.max_anisotropy < major && minor > 0.0f) {
      const float widen = major / (minor * options.max_anisotropy);
      ey = {ey.x * widen, ey.y * widen};
      minor *= widen;
    }
    if (minor == 0.0f) return bilinear(0, a, b, 1.0f, visit);
    if (!(minor < float(1 << 30))) return visit_one(texel(top, 0, 0), visit);
    // The level where a texel spans the minor axis, and the next coarser one, blended.
    const float lod = std::fmax(0.0f, std::log2(minor));
    const int i = int(std::floor(lod));
    const float t = lod - float(i);
    ewa(i, a, b, ex, ey, 1.0f - t, visit);
    if (t > 0.0f) ewa(i + 1, a, b, ex, ey, t, visit);
  }

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<Texel> texels;
  };
  std::vector<Level> levels_;

  static int wrap(int i, int n) {
    const int r = i % n;
    return r < 0 ? r + n : r;
  }
  static float dot2(Vec2 v) { return v.x * v.x + v.y * v.y; }

  template <typename Visit>
  static void visit_one(const Texel& t, Visit& visit) {
    const Texel* texels[4] = {&t, &t, &t, &t};
    const float weights[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    visit(texels, weights);
  }

  // The four texels around image point (a, b) of a level, their bilinear weights times `weight`.
  template <typename Visit>
  void bilinear(int level, float a, float b, float weight, Visit& visit) const {
    const float x = a * float(width(level)) - 0.5f, y = b * float(height(level)) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    const int x0 = int(fx), y0 = int(fy);
    const Texel* texels[4] = {&texel(level, x0, y0), &texel(level, x0 + 1, y0), &texel(level, x0, y0 + 1),
                              &texel(level, x0 + 1, y0 + 1)};
    const float weights[4] = {weight * (1 - tx) * (1 - ty), weight * tx * (1 - ty), weight * (1 - tx) * ty,
                              weight * tx * ty};
    visit(texels, weights);
  }

  // Heckbert's EWA on one level: the texels inside the ellipse spanned by the axes e0, e1 (level-0 texels) around
  // (a, b), each weighted by ewa_gaussian_weight of its elliptical radius, normalised to `weight` in all. The
  // implicit ellipse A x² + B x y + C y² = F of axes e0, e1 has A = e0.y² + e1.y², B = −2(e0.x e0.y + e1.x e1.y),
  // C = e0.x² + e1.x², F = AC − B²/4; adding 1 to A and C first (Heckbert's reconstruction term) keeps it at least
  // a texel wide. Two passes over the bounding box: the weights' sum, then the texels.
  template <typename Visit>
  void ewa(int level, float a, float b, Vec2 e0, Vec2 e1, float weight, Visit& visit) const {
    if (level >= levels() - 1) return visit_scaled(texel(levels() - 1, 0, 0), weight, visit);
    const float sx = float(width(level)) / float(width(0)), sy = float(height(level)) / float(height(0));
    const float cx = a * float(width(level)) - 0.5f, cy = b * float(height(level)) - 0.5f;
    e0 = {e0.x * sx, e0.y * sy};
    e1 = {e1.x * sx, e1.y * sy};
    float A = e0.y * e0.y + e1.y * e1.y + 1.0f;
    float B = -2.0f * (e0.x * e0.y + e1.x * e1.y);
    float C = e0.x * e0.x + e1.x * e1.x + 1.0f;
    const float inv_f = 1.0f / (A * C - 0.25f * B * B);
    A *= inv_f, B *= inv_f, C *= inv_f;
    // The bounding box of A x² + B x y + C y² = 1: |x| ≤ √(4C/det), |y| ≤ √(4A/det), det = 4AC − B².
    const float det = 4.0f * A * C - B * B;
    const float half_x = std::sqrt(std::fmax(0.0f, 4.0f * C / det)), half_y = std::sqrt(std::fmax(0.0f, 4.0f * A / det));
    const int x0 = int(std::ceil(cx - half_x)), x1 = int(std::floor(cx + half_x));
    const int y0 = int(std::ceil(cy - half_y)), y1 = int(std::floor(cy + half_y));
    const auto each = [&](auto&& texel_weight) {
      for (int y = y0; y <= y1; ++y) {
        const float dy = float(y) - cy;
        for (int x = x0; x <= x1; ++x) {
          const float dx = float(x) - cx;
          const float r2 = A * dx * dx + B * dx * dy + C * dy * dy;
          if (r2 < 1.0f) texel_weight(x, y, ewa_gaussian_weight(r2));
        }
      }
    };
    float total = 0.0f;
    each([&](int, int, float w) { total += w; });
    if (!(total > 0.0f)) return bilinear(level, a, b, weight, visit);
    const float norm = weight / total;
    const Texel* texels[4];
    float weights[4];
    int n = 0;
    each([&](int x, int y, float w) {
      texels[n] = &texel(level, x, y);
      weights[n] = w * norm;
      if (++n == 4) {
        visit(texels, weights);
        n = 0;
      }
    });
    if (n > 0) {
      for (int j = n; j < 4; ++j) texels[j] = texels[0], weights[j] = 0.0f;
      visit(texels, weights);
    }
  }

  template <typename Visit>
  static void visit_scaled(const Texel& t, float weight, Visit& visit) {
    const Texel* texels[4] = {&t, &t, &t, &t};
    const float weights[4] = {weight, 0.0f, 0.0f, 0.0f};
    visit(texels, weights);
  }

  // The area-weighted box filter of one axis: output texel i covers [i·n/m, (i+1)·n/m) of the n input texels.
  struct AxisTap {
    int first = 0;
    std::array<float, 3> weight{};  // at most three input texels overlap one output texel (n/m ≤ 3)
  };
  static std::vector<AxisTap> axis_taps(int n, int m) {
    std::vector<AxisTap> taps(static_cast<size_t>(m));
    const double span = double(n) / double(m);
    for (int i = 0; i < m; ++i) {
      const double lo = i * span, hi = (i + 1) * span;
      AxisTap& tap = taps[size_t(i)];
      tap.first = int(std::floor(lo));
      for (int j = tap.first; j < std::min(n, tap.first + 3); ++j) {
        const double overlap = std::min(hi, double(j + 1)) - std::max(lo, double(j));
        if (overlap > 0.0) tap.weight[size_t(j - tap.first)] = float(overlap / span);
      }
    }
    return taps;
  }

  template <typename Codec>
  static Level downsampled(const Level& fine, const Codec& codec) {
    using Linear = typename Codec::Linear;
    Level coarse;
    coarse.width = std::max(1, fine.width / 2);
    coarse.height = std::max(1, fine.height / 2);
    const std::vector<AxisTap> tx = axis_taps(fine.width, coarse.width), ty = axis_taps(fine.height, coarse.height);
    // Rows first, then columns, one coarse row at a time: the fine rows it covers are filtered across into `across`
    // and summed into `sum` (two coarse rows of Linear values, not a whole level: a fine row shared by two coarse
    // rows is filtered twice).
    coarse.texels.resize(size_t(coarse.width) * size_t(coarse.height));
    std::vector<Linear> across(size_t(coarse.width)), sum(size_t(coarse.width));
    for (int y = 0; y < coarse.height; ++y) {
      std::fill(sum.begin(), sum.end(), Linear{});
      const AxisTap& row_tap = ty[size_t(y)];
      for (int k = 0; k < 3; ++k) {
        if (!(row_tap.weight[size_t(k)] > 0.0f)) continue;
        const size_t fine_row = size_t(row_tap.first + k) * size_t(fine.width);
        for (int x = 0; x < coarse.width; ++x) {
          Linear acc{};
          const AxisTap& tap = tx[size_t(x)];
          for (int j = 0; j < 3; ++j)
            if (tap.weight[size_t(j)] > 0.0f)
              add_scaled(acc, codec.decode(fine.texels[fine_row + size_t(tap.first + j)]), tap.weight[size_t(j)]);
          across[size_t(x)] = acc;
        }
        for (int x = 0; x < coarse.width; ++x) add_scaled(sum[size_t(x)], across[size_t(x)], row_tap.weight[size_t(k)]);
      }
      for (int x = 0; x < coarse.width; ++x)
        coarse.texels[size_t(y) * size_t(coarse.width) + size_t(x)] = codec.encode(sum[size_t(x)]);
    }
    return coarse;
  }
};

}  // namespace rimu
