#include "render/film/pixel_filter.h"

#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "spectral/error.h"

namespace rimu {
namespace {

constexpr int kKnotsPerAxis = 257;

// Harris 1978, "On the use of windows for harmonic analysis with the discrete Fourier transform", Proc. IEEE
// 66(1):51-83, the 4-term (−92 dB) Blackman–Harris window.
constexpr double kBlackmanHarris[4] = {0.35875, 0.48829, 0.14128, 0.01168};

void require_positive(float value, const char* what) {
  if (!(value > 0.0f) || !std::isfinite(value))
    throw InputError({"", 0, "film/filter"}, std::string("the pixel filter's ") + what +
                                                 " must be a positive number of pixels; got " + std::to_string(value));
}

}  // namespace

PixelFilter::PixelFilter(Kind kind, float radius_px, float sigma_px)
    : kind_(kind), radius_px_(radius_px), sigma_px_(sigma_px) {
  std::vector<double> knots(kKnotsPerAxis);
  for (int i = 0; i < kKnotsPerAxis; ++i)
    knots[i] = std::max(0.0, profile(-radius_px + 2.0 * radius_px * i / (kKnotsPerAxis - 1)));
  axis_ = std::make_shared<PiecewiseLinearDistribution>(-radius_px, radius_px, std::move(knots));
}

PixelFilter PixelFilter::box(float radius_px) {
  require_positive(radius_px, "radius");
  return PixelFilter(Kind::box, radius_px, 0.0f);
}

PixelFilter PixelFilter::triangle(float radius_px) {
  require_positive(radius_px, "radius");
  return PixelFilter(Kind::triangle, radius_px, 0.0f);
}

PixelFilter PixelFilter::gaussian(float radius_px, float sigma_px) {
  require_positive(radius_px, "radius");
  require_positive(sigma_px, "sigma");
  return PixelFilter(Kind::gaussian, radius_px, sigma_px);
}

PixelFilter PixelFilter::blackman_harris(float radius_px) {
  require_positive(radius_px, "radius");
  return PixelFilter(Kind::blackman_harris, radius_px, 0.0f);
}

double PixelFilter::profile(double x) const {
  const double r = radius_px_;
  if (!(std::abs(x) <= r)) return 0.0;
  switch (kind_) {
    case Kind::box:
      return 1.0;
    case Kind::triangle:
      return r - std::abs(x);
    case Kind::gaussian: {
      const double s2 = 2.0 * double(sigma_px_) * sigma_px_;
      return std::max(0.0, std::exp(-x * x / s2) - std::exp(-r * r / s2));
    }
    case Kind::blackman_harris: {
      const double phase = std::numbers::pi * x / r;
      return kBlackmanHarris[0] + kBlackmanHarris[1] * std::cos(phase) + kBlackmanHarris[2] * std::cos(2.0 * phase) +
             kBlackmanHarris[3] * std::cos(3.0 * phase);
    }
  }
  return 0.0;
}

FilterSample PixelFilter::sample(Vec2 u) const {
  // The filter is separable and so is p: x and y are independent draws from the same 1D distribution.
  return {Vec2{float(axis_->sample(u.x)), float(axis_->sample(u.y))}, 1.0f};
}

std::string PixelFilter::description() const {
  std::ostringstream s;
  switch (kind_) {
    case Kind::box: s << "box (radius " << radius_px_ << " px)"; break;
    case Kind::triangle: s << "triangle (radius " << radius_px_ << " px)"; break;
    case Kind::gaussian: s << "gaussian (radius " << radius_px_ << " px, sigma " << sigma_px_ << " px)"; break;
    case Kind::blackman_harris: s << "blackman-harris (radius " << radius_px_ << " px)"; break;
  }
  return s.str();
}

}  // namespace rimu
