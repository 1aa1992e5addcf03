// The emission of an area light that varies over its surface: radiance read from an image at the surface's texture
// coordinates (a screen, a lamp shade, signage; pbrt-v4's `AreaLightSource "diffuse"` with `filename`).
//
// Lookup: bilinear between the four nearest pixels' spectra, pixel centres at ((x + ½)/w, (y + ½)/h), v = 0 at the
// BOTTOM row (as image textures, RgbImage::bilinear, and as pbrt-v4's area light, which flips v), clamped at the
// edges (pbrt-v4's area light lookup clamps; a texture repeats). Interpolating spectra rather than RGB keeps the
// lookup linear: between two pixels the radiance is their mix, never a colour neither has.
//
// The light's triangles carry their corners' uv (the same affine map the geometry gives a hit), so a point sampled on
// a triangle finds the same radiance a ray that hits it there sees.
//
// What the light sampler needs (AreaLight): each triangle's mean radiance integral ∫L dλ over its area, estimated
// once from a stratified grid of points in the triangle (more points where the triangle spans more pixels); the mean
// is for choosing triangles and for power, not for the estimate, so its error costs variance, never bias. A floor
// of 10⁻³ of the whole light's mean keeps every triangle choosable, so a bright pixel that the grid missed is still
// found (unbiased).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "transport/geometry/vector.h"
#include "transport/lights/radiance_image.h"

namespace rimu {

class TexturedEmission {
 public:
  /// `image`'s radiance times `scale` (finite, ≥ 0; the loader's units: W/(m²·sr·nm) per image unit).
  /// `corner_uvs[k]`: the texture coordinates of triangle k at its vertices 0, 1, 2. Cost: one pass over the pixels
  /// (their ∫L dλ, 16 wavelengths).
  TexturedEmission(std::shared_ptr<const RadianceImage> image, double scale,
                   std::vector<std::array<Vec2, 3>> corner_uvs);

  /// Radiance at texture coordinates `uv` (per sample: four pixel lookups).
  SampledSpectrum radiance(Vec2 uv, const SampledWavelengths& lambda) const;
  /// The texture coordinates of triangle k at barycentrics (b0, b1, b2).
  Vec2 uv_at(size_t triangle, Vec3 barycentric) const {
    const auto& c = corner_uvs_[triangle];
    return {c[0].x * barycentric.x + c[1].x * barycentric.y + c[2].x * barycentric.z,
            c[0].y * barycentric.x + c[1].y * barycentric.y + c[2].y * barycentric.z};
  }
  /// ∫L dλ over 360-830 nm (W/(m²·sr)) averaged over triangle k's area, estimated (see above); ≥ 0.
  double triangle_mean_radiance_integral(size_t triangle) const;
  size_t triangle_count() const { return corner_uvs_.size(); }

  /// The share of the whole light's mean radiance integral below which no triangle's sampling weight falls.
  static constexpr double kWeightFloor = 1e-3;

 private:
  /// ∫L dλ at uv, bilinear between pixels as radiance() (setup only).
  double radiance_integral(Vec2 uv) const;
  /// The four pixels and weights of a bilinear lookup at uv.
  struct Footprint {
    int x0, x1, y0, y1;
    float fx, fy;
  };
  Footprint footprint(Vec2 uv) const;

  std::shared_ptr<const RadianceImage> image_;
  float scale_;
  int width_, height_;
  std::vector<std::array<Vec2, 3>> corner_uvs_;
  std::vector<float> pixel_integral_;  // ∫L dλ of each pixel times scale, row-major, row 0 at the top
};

}  // namespace rimu
