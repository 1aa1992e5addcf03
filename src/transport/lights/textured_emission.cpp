#include "transport/lights/textured_emission.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "transport/lights/light_warps.h"

namespace rimu {

namespace {
/// Points per side of the stratified grid in a triangle's mean: at least 4 × 4, at most 32 × 32, about two points per
/// pixel the triangle spans in between.
constexpr int kMinGridSide = 4, kMaxGridSide = 32;
}  // namespace

TexturedEmission::TexturedEmission(std::shared_ptr<const RadianceImage> image, double scale,
                                   std::vector<std::array<Vec2, 3>> corner_uvs)
    : image_(std::move(image)), scale_(float(scale)), corner_uvs_(std::move(corner_uvs)) {
  assert(image_ && image_->width() > 0 && image_->height() > 0 && std::isfinite(scale) && scale >= 0.0);
  width_ = image_->width();
  height_ = image_->height();
  pixel_integral_.resize(size_t(width_) * size_t(height_));
  std::vector<double> row_integrals(width_);
  for (int y = 0; y < height_; ++y) {
    image_->radiance_integrals(y, row_integrals);
    for (int x = 0; x < width_; ++x)
      pixel_integral_[size_t(y) * size_t(width_) + size_t(x)] = float(std::max(0.0, scale * row_integrals[x]));
  }
}

TexturedEmission::Footprint TexturedEmission::footprint(Vec2 uv) const {
  // Continuous pixel coordinates with centres at integers; v = 0 at the bottom row. NaN uv (never from finite
  // geometry) would fail the clamps' comparisons: map it to pixel 0 rather than index out of range.
  const float px = std::isfinite(uv.x) ? uv.x * float(width_) - 0.5f : 0.0f;
  const float py = std::isfinite(uv.y) ? (1.0f - uv.y) * float(height_) - 0.5f : 0.0f;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  Footprint f;
  f.fx = px - fx0;
  f.fy = py - fy0;
  const auto clamp_x = [&](float v) { return int(std::clamp(v, 0.0f, float(width_ - 1))); };
  const auto clamp_y = [&](float v) { return int(std::clamp(v, 0.0f, float(height_ - 1))); };
  f.x0 = clamp_x(fx0);
  f.x1 = clamp_x(fx0 + 1.0f);
  f.y0 = clamp_y(fy0);
  f.y1 = clamp_y(fy0 + 1.0f);
  return f;
}

SampledSpectrum TexturedEmission::radiance(Vec2 uv, const SampledWavelengths& lambda) const {
  const Footprint f = footprint(uv);
  const SampledSpectrum top = image_->radiance(f.x0, f.y0, lambda) * Float4(1.0f - f.fx) +
                              image_->radiance(f.x1, f.y0, lambda) * Float4(f.fx);
  const SampledSpectrum bottom = image_->radiance(f.x0, f.y1, lambda) * Float4(1.0f - f.fx) +
                                 image_->radiance(f.x1, f.y1, lambda) * Float4(f.fx);
  return (top * Float4(1.0f - f.fy) + bottom * Float4(f.fy)) * Float4(scale_);
}

double TexturedEmission::radiance_integral(Vec2 uv) const {
  const Footprint f = footprint(uv);
  const auto at = [&](int x, int y) { return double(pixel_integral_[size_t(y) * size_t(width_) + size_t(x)]); };
  const double top = at(f.x0, f.y0) * (1.0 - f.fx) + at(f.x1, f.y0) * f.fx;
  const double bottom = at(f.x0, f.y1) * (1.0 - f.fx) + at(f.x1, f.y1) * f.fx;
  return top * (1.0 - f.fy) + bottom * f.fy;
}

double TexturedEmission::triangle_mean_radiance_integral(size_t triangle) const {
  assert(triangle < corner_uvs_.size());
  const auto& c = corner_uvs_[triangle];
  // The pixels the triangle spans: its uv area times the image's pixel count.
  const double uv_area = 0.5 * std::fabs(double(c[1].x - c[0].x) * double(c[2].y - c[0].y) -
                                         double(c[2].x - c[0].x) * double(c[1].y - c[0].y));
  const double pixels = uv_area * double(width_) * double(height_);
  const int side = std::clamp(int(std::ceil(std::sqrt(2.0 * std::min(pixels, 1e6)))), kMinGridSide, kMaxGridSide);
  double total = 0.0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      // Cell centres of a side × side grid, warped to uniform points on the triangle (area-preserving).
      const Vec3 b = sample_uniform_triangle({(float(i) + 0.5f) / float(side), (float(j) + 0.5f) / float(side)});
      total += radiance_integral(uv_at(triangle, b));
    }
  return total / (double(side) * double(side));
}

}  // namespace rimu
