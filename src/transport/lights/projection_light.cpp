#include "transport/lights/projection_light.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

#include "transport/lights/point_light.h"

namespace rimu {

namespace {
/// Directions closer to the image plane than this (w·n/|w|) emit nothing: pbrt-v4's hither.
constexpr float kHither = 1e-3f;
}  // namespace

ProjectionLight::ProjectionLight(Vec3 position_m, Frame frame, double fov_deg,
                                 std::shared_ptr<const RadianceImage> image, double scale)
    : position_m_(position_m), frame_(frame), image_(std::move(image)), scale_(float(scale)) {
  assert(image_ && image_->width() > 0 && image_->height() > 0 && std::isfinite(scale) && scale >= 0.0);
  assert(fov_deg > 0.0 && fov_deg < 180.0);
  tan_half_fov_ = float(std::tan(fov_deg * std::numbers::pi / 360.0));
  const double aspect = double(image_->width()) / double(image_->height());
  half_width_ = aspect > 1.0 ? float(aspect) : 1.0f;
  half_height_ = aspect > 1.0 ? 1.0f : float(1.0 / aspect);

  const int w = image_->width(), h = image_->height();
  // A pixel's patch of the image plane at distance 1 is the rectangle [x0, x1] × [y0, y1], of side
  // 2·half_width·tan/w by 2·half_height·tan/h; its solid angle ∫ cos³θ dA is exact by the corner function
  // F(x, y) = atan(xy/√(1 + x² + y²)), the solid angle of [0, x] × [0, y] (pbrt-v4 takes cos³θ at the pixel's centre
  // times its area, which is a few per cent off for coarse images at wide angles).
  const double tan = tan_half_fov_;
  const double pixel_w = 2.0 * half_width_ * tan / w, pixel_h = 2.0 * half_height_ * tan / h;
  const auto corner = [](double x, double y) { return std::atan(x * y / std::sqrt(1.0 + x * x + y * y)); };
  std::vector<double> row_integrals(w);
  for (int y = 0; y < h; ++y) {
    image_->radiance_integrals(y, row_integrals);
    for (int x = 0; x < w; ++x) {
      const double integral = std::max(0.0, scale * row_integrals[x]);
      brightest_integral_ = std::max(brightest_integral_, integral);
      const double x0 = -half_width_ * tan + x * pixel_w, x1 = x0 + pixel_w;
      const double y1 = half_height_ * tan - y * pixel_h, y0 = y1 - pixel_h;  // row 0 at the top
      const double solid_angle_sr = corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
      power_w_ += integral * solid_angle_sr;
      luminance_solid_angle_sr_ += std::max(0.0f, image_->luminance(x, y)) * solid_angle_sr;
    }
  }
}

std::pair<int, int> ProjectionLight::pixel_towards(Vec3 w_out) const {
  const Vec3 w = frame_.to_local(w_out);
  if (!(w.z > kHither * length(w))) return {-1, -1};
  const float sx = w.x / (w.z * tan_half_fov_), sy = w.y / (w.z * tan_half_fov_);
  if (!(std::fabs(sx) <= half_width_) || !(std::fabs(sy) <= half_height_)) return {-1, -1};
  const int width = image_->width(), height = image_->height();
  const int column = std::min(width - 1, int((sx + half_width_) / (2.0f * half_width_) * float(width)));
  const int row = std::min(height - 1, int((half_height_ - sy) / (2.0f * half_height_) * float(height)));
  return {std::max(0, column), std::max(0, row)};
}

double ProjectionLight::corner_angle_rad() const {
  return std::atan(double(tan_half_fov_) * std::hypot(double(half_width_), double(half_height_)));
}

std::optional<LightSample> ProjectionLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                      Vec2) const {
  const Vec3 to_reference = ref.position - position_m_;
  const float distance = length(to_reference);
  if (!(distance > 0.0f) || !std::isfinite(distance)) return std::nullopt;
  const auto [column, row] = pixel_towards(to_reference / distance);
  if (column < 0) return std::nullopt;
  const SampledSpectrum intensity = image_->radiance(column, row, lambda) * Float4(scale_);
  if (!(max_lane(intensity) > 0.0f)) return std::nullopt;
  return delta_position_sample(position_m_, ref, intensity);
}

double ProjectionLight::total_power_w(double) const { return power_w_; }

std::optional<LightBounds> ProjectionLight::part_bounds(int part) const {
  if (part != 0 || !(brightest_integral_ > 0.0)) return std::nullopt;
  return point_light_bounds(position_m_, brightest_integral_, frame_.n, corner_angle_rad(), 0.0);
}

}  // namespace rimu
