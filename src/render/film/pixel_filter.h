// The pixel reconstruction filter, applied by importance-sampling each camera sample's offset from the pixel centre.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "render/film/piecewise_linear_distribution.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// A camera sample's offset from the pixel centre, in pixels, and its filter weight.
struct FilterSample {
  Vec2 offset_px;
  float weight = 1.0f;  ///< f(offset) / pdf(offset) × ∫f: exactly 1 for the (positive) filters here
};

/// A separable filter f(x, y) = f₁(x) f₁(y) on [−r, r]², used by importance sampling rather than splatting:
/// the camera draws the sample position at the pixel centre + an offset with density p ∝ |f|, and the film
/// averages with weight f/p·∫f = sign(f). For positive filters the weight is the constant 1, so each sample
/// touches exactly one pixel (no splatting to neighbours, no locks, tile-local writes) and the pixel value is the
/// plain sample mean: the filtered image ∫ f(o) I(centre + o) do / ∫ f.
///
/// Each axis is sampled by inverting the CDF of f₁ tabulated at 257 equally spaced knots and linearly
/// interpolated (PiecewiseLinearDistribution). The filter actually applied is therefore that interpolant:
/// the box exactly, a smooth filter within h²/8·max|f₁''| (h = r/128): < 1e-4 of the peak for the defaults.
/// f₁ per filter:
/// - box:             1
/// - triangle:        r − |x|  (pbrt-v4's TriangleFilter; piecewise linear, so the tabulation is exact)
/// - Gaussian:        exp(−x²/2σ²) − exp(−r²/2σ²)  (shifted so it reaches 0 at the radius instead of jumping)
/// - Blackman–Harris: a₀ + a₁cos(πx/r) + a₂cos(2πx/r) + a₃cos(3πx/r) with the 4-term −92 dB coefficients
///   (0.35875, 0.48829, 0.14128, 0.01168) of Harris 1978 (Proc. IEEE 66(1)), centred on 0: the window
///   ends at a₀ − a₁ + a₂ − a₃ = 6e-5 > 0, so it is positive everywhere.
class PixelFilter {
 public:
  enum class Kind { box, triangle, gaussian, blackman_harris };

  /// The box of half-width radius_px (0.5 = the pixel itself). Throws InputError unless radius > 0.
  static PixelFilter box(float radius_px = 0.5f);
  /// The tent of half-width radius_px (pbrt-v4's default: 2). Throws InputError unless radius > 0.
  static PixelFilter triangle(float radius_px = 2.0f);
  /// Truncated Gaussian of standard deviation sigma_px, cut at radius_px. Throws InputError unless both > 0.
  static PixelFilter gaussian(float radius_px = 1.5f, float sigma_px = 0.5f);
  /// Blackman–Harris window of half-width radius_px. Throws InputError unless radius > 0.
  static PixelFilter blackman_harris(float radius_px = 2.0f);

  /// The filter's 1D profile f₁(x) as defined above (analytic, unnormalised; 0 for |x| > r).
  double profile(double x_px) const;
  /// f(x, y) = f₁(x) f₁(y) (analytic, unnormalised).
  double evaluate(Vec2 offset_px) const { return profile(offset_px.x) * profile(offset_px.y); }
  /// The density of sample()'s offsets, per pixel² (the normalised tabulated filter).
  double pdf(Vec2 offset_px) const { return axis_->pdf(offset_px.x) * axis_->pdf(offset_px.y); }
  /// An offset with density pdf(), from two uniform numbers in [0, 1); weight 1. Cost: two binary searches.
  FilterSample sample(Vec2 u) const;
  /// Spreads a contribution at film point `film_px` (a light-traced splat, a Metropolis sample) over the pixels the
  /// filter reaches, by the density a camera sample of each pixel would have landed there with: calls
  /// `add(x, y, density)` for each pixel (x, y) with x0 ≤ x < x1, y0 ≤ y < y1 and density > 0.
  template <typename Add>
  void spread(Vec2 film_px, int x0, int y0, int x1, int y1, Add&& add) const {
    const int px0 = std::max(x0, int(std::floor(film_px.x - 0.5f - radius_px_)));
    const int px1 = std::min(x1 - 1, int(std::ceil(film_px.x - 0.5f + radius_px_)));
    const int py0 = std::max(y0, int(std::floor(film_px.y - 0.5f - radius_px_)));
    const int py1 = std::min(y1 - 1, int(std::ceil(film_px.y - 0.5f + radius_px_)));
    for (int py = py0; py <= py1; ++py)
      for (int px = px0; px <= px1; ++px) {
        const double density = pdf({film_px.x - (float(px) + 0.5f), film_px.y - (float(py) + 0.5f)});
        if (density > 0.0) add(px, py, density);
      }
  }

  Kind kind() const { return kind_; }
  float radius_px() const { return radius_px_; }
  float sigma_px() const { return sigma_px_; }
  /// e.g. "gaussian (radius 1.5 px, sigma 0.5 px)".
  std::string description() const;

 private:
  PixelFilter(Kind kind, float radius_px, float sigma_px);

  Kind kind_;
  float radius_px_, sigma_px_;
  std::shared_ptr<const PiecewiseLinearDistribution> axis_;  // immutable, shared by copies
};

}  // namespace rimu
