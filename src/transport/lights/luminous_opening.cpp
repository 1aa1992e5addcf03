#include "transport/lights/luminous_opening.h"
#include "spectral/math_constants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace rimu {
namespace {


std::string format(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

LuminousOpening LuminousOpening::rectangle(double length_m, double width_m) {
  LuminousOpening o;
  o.shape_ = Shape::rectangle;
  o.a_ = length_m;
  o.b_ = width_m;
  return o;
}

LuminousOpening LuminousOpening::disc(double diameter_m) {
  LuminousOpening o;
  o.shape_ = Shape::disc;
  o.a_ = 0.5 * diameter_m;
  return o;
}

LuminousOpening LuminousOpening::box(double length_m, double width_m, double height_m) {
  LuminousOpening o;
  o.shape_ = Shape::box;
  o.a_ = length_m;
  o.b_ = width_m;
  o.h_ = height_m;
  return o;
}

LuminousOpening LuminousOpening::cylinder(double diameter_m, double height_m) {
  LuminousOpening o;
  o.shape_ = Shape::cylinder;
  o.a_ = 0.5 * diameter_m;
  o.h_ = height_m;
  return o;
}

LuminousOpening LuminousOpening::sphere(double diameter_m) {
  LuminousOpening o;
  o.shape_ = Shape::sphere;
  o.a_ = 0.5 * diameter_m;
  return o;
}

LuminousOpeningFromLm63 luminous_opening_from_lm63(double width, double length, double height, double metres_per_unit) {
  const double w = width * metres_per_unit, l = length * metres_per_unit, h = height * metres_per_unit;
  const auto unsupported = [&](const std::string& what) {
    return LuminousOpeningFromLm63{std::nullopt, "width " + format(width) + ", length " + format(length) + ", height " + format(height) +
                                      ": " + what};
  };
  if (w == 0 && l == 0 && h == 0) return {LuminousOpening(), {}};
  if (w > 0 && l > 0 && h == 0) return {LuminousOpening::rectangle(l, w), {}};
  if (w > 0 && l > 0 && h > 0) return {LuminousOpening::box(l, w, h), {}};
  if (w < 0 && w == l && h == 0) return {LuminousOpening::disc(-w), {}};
  if (w < 0 && w == l && h > 0) return {LuminousOpening::cylinder(-w, h), {}};
  if (w < 0 && w == l && h == w) return {LuminousOpening::sphere(-w), {}};
  if (w < 0 && l < 0 && w != l && h <= 0) return unsupported("an ellipse or ellipsoid, which Rimu does not model");
  return unsupported("not a luminous opening Rimu models (a point, rectangle, box, disc, vertical cylinder or sphere)");
}

const char* LuminousOpening::name() const {
  switch (shape_) {
    case Shape::point: return "point";
    case Shape::rectangle: return "rectangle";
    case Shape::disc: return "disc";
    case Shape::box: return "box";
    case Shape::cylinder: return "cylinder";
    case Shape::sphere: return "sphere";
  }
  return "point";
}

double LuminousOpening::area_m2() const {
  switch (shape_) {
    case Shape::point: return 0.0;
    case Shape::rectangle: return a_ * b_;
    case Shape::disc: return kPi * a_ * a_;
    case Shape::box: return 2.0 * (a_ * b_ + a_ * h_ + b_ * h_);
    case Shape::cylinder: return 2.0 * kPi * a_ * a_ + 2.0 * kPi * a_ * h_;
    case Shape::sphere: return 4.0 * kPi * a_ * a_;
  }
  return 0.0;
}

double LuminousOpening::projected_area_m2(Vec3 w) const {
  const double x = std::fabs(w.x), y = std::fabs(w.y), z = std::fabs(w.z);
  switch (shape_) {
    case Shape::point: return 0.0;
    case Shape::rectangle: return a_ * b_ * z;
    case Shape::disc: return kPi * a_ * a_ * z;
    case Shape::box: return b_ * h_ * x + a_ * h_ * y + a_ * b_ * z;
    case Shape::cylinder: return kPi * a_ * a_ * z + 2.0 * a_ * h_ * std::sqrt(std::max(0.0, 1.0 - z * z));
    case Shape::sphere: return kPi * a_ * a_;
  }
  return 0.0;
}

Vec3 LuminousOpening::half_extent_m() const {
  switch (shape_) {
    case Shape::point: return {0, 0, 0};
    case Shape::rectangle: return {float(0.5 * a_), float(0.5 * b_), 0};
    case Shape::disc: return {float(a_), float(a_), 0};
    case Shape::box: return {float(0.5 * a_), float(0.5 * b_), float(0.5 * h_)};
    case Shape::cylinder: return {float(a_), float(a_), float(0.5 * h_)};
    case Shape::sphere: return {float(a_), float(a_), float(a_)};
  }
  return {0, 0, 0};
}

LuminousOpening::SurfacePoint LuminousOpening::sample(Vec2 u) const {
  const double u0 = u.x, u1 = u.y;
  // A point uniform on a disc of radius r at height z (concentric would do as well; area is what matters).
  const auto disc_point = [](double r, double s, double t, double z) {
    const double radius = r * std::sqrt(s), phi = 2.0 * kPi * t;
    return Vec3{float(radius * std::cos(phi)), float(radius * std::sin(phi)), float(z)};
  };
  switch (shape_) {
    case Shape::point: return {{0, 0, 0}, {0, 0, 1}};
    case Shape::rectangle: return {{float((u0 - 0.5) * a_), float((u1 - 0.5) * b_), 0}, {0, 0, 1}};
    case Shape::disc: return {disc_point(a_, u0, u1, 0.0), {0, 0, 1}};
    case Shape::box: {
      // Faces in pairs by area: ±z (a·b), ±x (b·h), ±y (a·h); u0 picks the face, then is rescaled.
      const double areas[3] = {a_ * b_, b_ * h_, a_ * h_};
      const double total = areas[0] + areas[1] + areas[2];
      double t = u0 * total;
      int pair = 0;
      while (pair < 2 && t >= areas[pair]) t -= areas[pair++];
      const double s = std::min(t / areas[pair], 1.0);  // in [0, 1): which side and where along one edge
      const bool positive = s < 0.5;
      const double along = positive ? 2.0 * s : 2.0 * s - 1.0;
      const float sign = positive ? 1.0f : -1.0f;
      if (pair == 0)
        return {{float((along - 0.5) * a_), float((u1 - 0.5) * b_), float(sign * 0.5 * h_)}, {0, 0, sign}};
      if (pair == 1)
        return {{float(sign * 0.5 * a_), float((along - 0.5) * b_), float((u1 - 0.5) * h_)}, {sign, 0, 0}};
      return {{float((along - 0.5) * a_), float(sign * 0.5 * b_), float((u1 - 0.5) * h_)}, {0, sign, 0}};
    }
    case Shape::cylinder: {
      const double cap = kPi * a_ * a_, side = 2.0 * kPi * a_ * h_;
      double t = u0 * (2.0 * cap + side);
      if (t < 2.0 * cap) {
        const bool top = t < cap;
        const double s = (top ? t : t - cap) / cap;
        const float sign = top ? 1.0f : -1.0f;
        return {disc_point(a_, std::min(s, 1.0), u1, sign * 0.5 * h_), {0, 0, sign}};
      }
      const double phi = 2.0 * kPi * std::min((t - 2.0 * cap) / side, 1.0);
      const Vec3 n{float(std::cos(phi)), float(std::sin(phi)), 0};
      return {{float(a_ * n.x), float(a_ * n.y), float((u1 - 0.5) * h_)}, n};
    }
    case Shape::sphere: {
      const double z = 1.0 - 2.0 * u0, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u1;
      const Vec3 n{float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
      return {{float(a_ * n.x), float(a_ * n.y), float(a_ * n.z)}, n};
    }
  }
  return {{0, 0, 0}, {0, 0, 1}};
}

double LuminousOpening::weight(Vec3 normal, Vec3 w) const {
  if (shape_ == Shape::point || shape_ == Shape::rectangle || shape_ == Shape::disc) return 1.0;
  const double facing = std::max(0.0, double(normal.x) * w.x + double(normal.y) * w.y + double(normal.z) * w.z);
  if (!(facing > 0.0)) return 0.0;
  const double projected = projected_area_m2(w);
  return projected > 0.0 ? area_m2() * facing / projected : 0.0;
}

}  // namespace rimu
