#include "transport/lights/environment_portal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace rimu {

namespace {

struct D3 {
  double x, y, z;
};
D3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(D3 a) { return std::sqrt(dot(a, a)); }
D3 scale(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
/// The z component of the unit vector along cross(a, b): all the set-up needs of the edge normals.
double unit_cross_z(D3 a, D3 b) {
  const D3 c = cross(a, b);
  return c.z / norm(c);
}

}  // namespace

std::optional<PortalRectangle> PortalRectangle::from_corners(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, float tolerance) {
  const Vec3 a = p1 - p0, b = p3 - p0;
  const float la = length(a), lb = length(b);
  const float longest = std::max(la, lb);
  if (!(longest > 0.0f) || !std::isfinite(longest) || std::min(la, lb) < 1e-6f * longest) return std::nullopt;
  // Opposite corner where a parallelogram puts it, and a right angle at p0.
  if (length(p2 - (p0 + a + b)) > tolerance * longest) return std::nullopt;
  if (std::fabs(dot(a, b)) > tolerance * la * lb) return std::nullopt;
  // Remove the component of b along a that the tolerance let through, so the set-up sees exact right angles.
  const Vec3 b_perpendicular = b - a * (dot(a, b) / (la * la));
  return PortalRectangle{p0, a, b_perpendicular};
}

double PortalRectangle::area_m2() const { return norm(cross(d3(edge_a), d3(edge_b))); }

Vec3 PortalRectangle::normal() const { return normalize(rimu::cross(edge_a, edge_b)); }

std::optional<SphericalRectangle> SphericalRectangle::make(const PortalRectangle& portal, Vec3 origin) {
  SphericalRectangle r;
  const D3 ea = d3(portal.edge_a), eb = d3(portal.edge_b), o = d3(origin);
  const double la = norm(ea), lb = norm(eb);
  D3 x = scale(ea, 1.0 / la), y = scale(eb, 1.0 / lb), z = cross(x, y);
  const D3 d = sub(d3(portal.corner), o);
  double z0 = dot(d, z);
  if (z0 > 0.0) {  // the paper's convention: the rectangle's plane below the origin
    z = scale(z, -1.0);
    z0 = -z0;
  }
  if (!(z0 < 0.0)) return std::nullopt;
  const double x0 = dot(d, x), y0 = dot(d, y), x1 = x0 + la, y1 = y0 + lb;
  // Normals of the four planes through the origin and an edge (only their z components are needed).
  const D3 v00{x0, y0, z0}, v01{x0, y1, z0}, v10{x1, y0, z0}, v11{x1, y1, z0};
  const double n0z = unit_cross_z(v00, v10), n1z = unit_cross_z(v10, v11), n2z = unit_cross_z(v11, v01),
               n3z = unit_cross_z(v01, v00);
  // Interior angles of the spherical rectangle: γ_i = acos(−n_i · n_{i+1}), where the normals' x/y parts make
  // n_i · n_{i+1} = n_i.z n_{i+1}.z (adjacent normals are perpendicular to a shared edge direction, §3 of the paper).
  const auto angle = [](double c) { return std::acos(std::clamp(c, -1.0, 1.0)); };
  const double g0 = angle(-n0z * n1z), g1 = angle(-n1z * n2z), g2 = angle(-n2z * n3z), g3 = angle(-n3z * n0z);
  r.k_ = 2.0 * std::numbers::pi - g2 - g3;
  r.solid_angle_sr_ = g0 + g1 - r.k_;
  if (!(r.solid_angle_sr_ > 0.0) || !std::isfinite(r.solid_angle_sr_)) return std::nullopt;
  r.b0_ = n0z;
  r.b1_ = n2z;
  r.x0_ = x0, r.y0_ = y0, r.z0_ = z0, r.x1_ = x1, r.y1_ = y1;
  r.origin_[0] = o.x, r.origin_[1] = o.y, r.origin_[2] = o.z;
  r.x_[0] = x.x, r.x_[1] = x.y, r.x_[2] = x.z;
  r.y_[0] = y.x, r.y_[1] = y.y, r.y_[2] = y.z;
  r.z_[0] = z.x, r.z_[1] = z.y, r.z_[2] = z.z;
  return r;
}

Vec3 SphericalRectangle::sample_point(Vec2 u) const {
  // Invert the solid angle of the sub-rectangle [x0, xu] × [y0, y1] for xu (the paper's eq. 7-8), then the
  // projected height along the chosen line for yv (eq. 10-11).
  const double au = double(u.x) * solid_angle_sr_ + k_;
  const double s = std::sin(au);
  const double fu = s != 0.0 ? (std::cos(au) * b0_ - b1_) / s : 0.0;
  double cu = std::clamp((fu > 0.0 ? 1.0 : -1.0) / std::sqrt(fu * fu + b0_ * b0_), -1.0, 1.0);
  const double sin_cu = std::sqrt(std::max(0.0, 1.0 - cu * cu));
  const double xu = sin_cu > 0.0 ? std::clamp(-(cu * z0_) / sin_cu, x0_, x1_) : (cu * z0_ > 0.0 ? x0_ : x1_);
  const double dist = std::sqrt(xu * xu + z0_ * z0_);
  const double h0 = y0_ / std::sqrt(dist * dist + y0_ * y0_), h1 = y1_ / std::sqrt(dist * dist + y1_ * y1_);
  const double hv = h0 + double(u.y) * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1.0 - 1e-12 ? std::clamp(hv * dist / std::sqrt(1.0 - hv2), y0_, y1_) : y1_;
  double p[3];
  for (int i = 0; i < 3; ++i) p[i] = origin_[i] + xu * x_[i] + yv * y_[i] + z0_ * z_[i];
  return {float(p[0]), float(p[1]), float(p[2])};
}

bool passes_through(const PortalRectangle& portal, Vec3 origin, Vec3 direction) {
  const D3 a = d3(portal.edge_a), b = d3(portal.edge_b), n = cross(a, b), w = d3(direction);
  const double denominator = dot(w, n);
  if (denominator == 0.0) return false;
  const D3 to_corner = sub(d3(portal.corner), d3(origin));
  const double t = dot(to_corner, n) / denominator;
  if (!(t > 0.0)) return false;
  const D3 p = sub(scale(w, t), to_corner);  // the hit point relative to the corner
  const double s = dot(p, a) / dot(a, a), r = dot(p, b) / dot(b, b);
  return s >= 0.0 && s <= 1.0 && r >= 0.0 && r <= 1.0;
}

double PortalSet::total_area_m2() const {
  double area = 0.0;
  for (const auto& p : portals_) area += p.area_m2();
  return area;
}

double PortalSet::total_solid_angle(Vec3 origin) const {
  double total = 0.0;
  for (const auto& p : portals_)
    if (const auto r = SphericalRectangle::make(p, origin)) total += r->solid_angle_sr();
  return total;
}

std::optional<PortalSet::Sample> PortalSet::sample(Vec3 origin, Vec2 u) const {
  if (portals_.empty()) return std::nullopt;
  // ΣΩ first (summed in total_solid_angle's order, so pdf() gets the same number), keeping the first kKept set-ups
  // for the choice (no allocation per sample; further portals are set up again).
  constexpr size_t kKept = 4;
  std::array<std::optional<SphericalRectangle>, kKept> kept;
  double total = 0.0;
  for (size_t i = 0; i < portals_.size(); ++i) {
    const auto rectangle = SphericalRectangle::make(portals_[i], origin);
    if (i < kKept) kept[i] = rectangle;
    if (rectangle) total += rectangle->solid_angle_sr();
  }
  if (!(total > 0.0)) return std::nullopt;
  // Portal k by Ω_k/ΣΩ; u.x is rescaled to [0,1) within the chosen portal's interval (rounding past the last
  // interval lands at its end).
  const double target = double(u.x) * total;
  const double below_one = double(std::nextafter(1.0f, 0.0f));
  double below = 0.0, ux = below_one;
  std::optional<SphericalRectangle> chosen;
  for (size_t i = 0; i < portals_.size(); ++i) {
    const auto rectangle = i < kKept ? kept[i] : SphericalRectangle::make(portals_[i], origin);
    if (!rectangle) continue;
    chosen = rectangle;
    const double omega = rectangle->solid_angle_sr();
    if (target < below + omega) {
      ux = std::clamp((target - below) / omega, 0.0, below_one);
      break;
    }
    below += omega;
  }
  const Vec3 to_point = chosen->sample_point({float(ux), u.y}) - origin;
  const float d = length(to_point);
  if (!(d > 0.0f) || !std::isfinite(d)) return std::nullopt;
  const Vec3 wi = to_point / d;
  // The density from the returned direction, as pdf() gives it (a direction on an edge shared by two portals, or
  // rounded just outside its own, gets the same number both ways); ΣΩ is already known.
  const float pdf_sr = pdf_given_total(origin, wi, total);
  if (!(pdf_sr > 0.0f)) return std::nullopt;
  return Sample{wi, pdf_sr};
}

float PortalSet::pdf(Vec3 origin, Vec3 wi) const {
  // Directions through no portal (most escaping rays) cost no spherical-rectangle set-up.
  for (const auto& p : portals_)
    if (passes_through(p, origin, wi)) return pdf_given_total(origin, wi, total_solid_angle(origin));
  return 0.0f;
}

float PortalSet::pdf_given_total(Vec3 origin, Vec3 wi, double total) const {
  int through = 0;
  for (const auto& p : portals_) through += passes_through(p, origin, wi) ? 1 : 0;
  if (through == 0 || !(total > 0.0)) return 0.0f;
  const float pdf_sr = float(through / total);
  return std::isfinite(pdf_sr) ? pdf_sr : 0.0f;
}

std::optional<LightBounds> portal_light_bounds(const PortalSet& portals, double radiance_w_m2_sr) {
  if (portals.empty() || !(radiance_w_m2_sr > 0.0)) return std::nullopt;
  LightBounds all;
  for (const PortalRectangle& p : portals.portals()) {
    const Vec3 c0 = p.corner, c1 = p.corner + p.edge_a, c2 = c1 + p.edge_b, c3 = p.corner + p.edge_b;
    const double half_area = 0.5 * p.area_m2();
    all = unite(all, triangle_light_bounds(c0, c1, c2, p.normal(), half_area, radiance_w_m2_sr, true));
    all = unite(all, triangle_light_bounds(c0, c2, c3, p.normal(), half_area, radiance_w_m2_sr, true));
  }
  if (!(all.intensity_w_sr > 0.0f)) return std::nullopt;
  return all;
}

}  // namespace rimu
