#include "spectral/upsampling/knot_gamut.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace rimu {
namespace {

double cross(Chromaticity o, Chromaticity a, Chromaticity b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

/// Andrew's monotone chain: the convex hull, counter-clockwise, without collinear points.
std::vector<Chromaticity> convex_hull(std::vector<Chromaticity> points) {
  std::sort(points.begin(), points.end(), [](Chromaticity a, Chromaticity b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  std::vector<Chromaticity> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

KnotGamut::KnotGamut(const KnotColorimetry& colorimetry) : white_(colorimetry.white()) {
  std::vector<Chromaticity> points;
  for (int i = 0; i < kUpsampleKnotCount; ++i) points.push_back(colorimetry.knot_chromaticity(i));
  vertices_ = convex_hull(std::move(points));
}

KnotGamut::KnotGamut(Chromaticity white, std::vector<Chromaticity> vertices)
    : white_(white), vertices_(std::move(vertices)) {}

double KnotGamut::boundary_radius(double angle_rad) const {
  // Solve white + t·d = a + u·(b − a) on each edge; the convex hull contains the white, so exactly one edge
  // is hit with t > 0 and u in [0, 1] (two at a vertex, with the same t).
  const double dx = std::cos(angle_rad), dy = std::sin(angle_rad);
  const size_t n = vertices_.size();
  for (size_t i = 0; i < n; ++i) {
    const Chromaticity a = vertices_[i], b = vertices_[(i + 1) % n];
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double denominator = dx * ey - dy * ex;
    if (denominator <= 0.0) continue;  // edge parallel to or facing away from the ray (counter-clockwise hull)
    const double wx = a.x - white_.x, wy = a.y - white_.y;
    const double t = (wx * ey - wy * ex) / denominator;
    const double u = (wx * dy - wy * dx) / denominator;
    if (u >= -1e-12 && u <= 1.0 + 1e-12 && t > 0.0) return t;
  }
  assert(false && "the white lies outside the knot gamut");
  return std::numeric_limits<double>::quiet_NaN();
}

double KnotGamut::relative_radius(Chromaticity xy) const {
  const double dx = xy.x - white_.x, dy = xy.y - white_.y;
  const double r = std::hypot(dx, dy);
  if (r == 0.0) return 0.0;
  return r / boundary_radius(std::atan2(dy, dx));
}

Chromaticity KnotGamut::at(double angle_rad, double relative_radius) const {
  const double r = relative_radius * boundary_radius(angle_rad);
  return {white_.x + r * std::cos(angle_rad), white_.y + r * std::sin(angle_rad)};
}

}  // namespace rimu
