#include "transport/lights/equal_area_intensity.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "transport/sampling/equal_area_square.h"

namespace rimu {

EqualAreaIntensity::EqualAreaIntensity(int resolution, std::vector<double> values)
    : resolution_(resolution), values_(std::move(values)) {
  assert(resolution_ >= 1 && values_.size() == size_t(resolution_) * size_t(resolution_));
  double sum = 0.0;
  for (double v : values_) {
    assert(std::isfinite(v) && v >= 0.0);
    sum += v;
    peak_ = std::max(peak_, v);
  }
  integral_ = 4.0 * std::numbers::pi * sum / (double(resolution_) * double(resolution_));
  pixels_ = Distribution2D(values_, resolution_, resolution_);
}

std::pair<int, int> EqualAreaIntensity::pixel_of(Vec3 w) const {
  const Vec2 uv = equal_area_sphere_to_square(w);
  const int x = std::clamp(int(uv.x * float(resolution_)), 0, resolution_ - 1);
  const int y = std::clamp(int(uv.y * float(resolution_)), 0, resolution_ - 1);
  return {x, y};
}

double EqualAreaIntensity::intensity(Vec3 w) const {
  const auto [x, y] = pixel_of(w);
  return pixel(x, y);
}

std::optional<IntensityDistribution::DirectionSample> EqualAreaIntensity::sample(Vec2 u) const {
  if (pixels_.is_zero()) return std::nullopt;
  const Distribution2D::Sample s = pixels_.sample(u);
  // dω = 4π du dv everywhere on the square.
  const double pdf = double(s.pdf) / (4.0 * std::numbers::pi);
  if (!(pdf > 0.0) || !std::isfinite(pdf)) return std::nullopt;
  return DirectionSample{equal_area_square_to_sphere(s.uv), float(pdf)};
}

float EqualAreaIntensity::pdf(Vec3 w) const {
  if (pixels_.is_zero()) return 0.0f;
  const auto [x, y] = pixel_of(w);
  const Vec2 centre{float((x + 0.5) / resolution_), float((y + 0.5) / resolution_)};
  return float(double(pixels_.pdf(centre)) / (4.0 * std::numbers::pi));
}

std::optional<std::pair<double, double>> EqualAreaIntensity::nonzero_gamma_rad() const {
  if (!(peak_ > 0.0)) return std::nullopt;
  return std::pair{0.0, std::numbers::pi};
}

}  // namespace rimu
