// Portals of an environment light: rectangles (windows, skylights) through which the environment is known to
// light the scene, so that next-event estimation samples only directions that pass through one.
//
// Geometry. A portal is a rectangle: a corner c and two perpendicular edges a, b (the others are c + a, c + a + b,
// c + b). It is two-sided for sampling: directions through it from either side are sampled.
//
// Sampling (Ureña, Fajardo & King 2013, "An Area-Preserving Parametrization for Spherical Rectangles", EGSR): the
// directions from a point o through a rectangle form a spherical rectangle of solid angle Ω(o); the parametrization
// maps [0,1)² onto it preserving area, so directions are uniform in solid angle, density 1/Ω(o). Computed in double:
// Ω = γ0 + γ1 − (2π − γ2 − γ3) cancels badly in float when the rectangle looks small.
//
// Several portals (PortalSet): portal k is chosen with probability Ω_k/ΣΩ, then a direction uniformly inside it, so
// the density of a direction ω is  N(o, ω) / ΣΩ,  N the number of portals the ray o + tω (t > 0) passes through
// (1 where the portals do not overlap as seen from o). pdf() computes exactly that. Where ΣΩ is 0 (o in the plane
// of every portal) nothing is sampled and the density is 0.
#pragma once

#include <optional>
#include <vector>

#include "transport/geometry/vector.h"
#include "transport/lights/light_bounds.h"

namespace rimu {

struct PortalRectangle {
  Vec3 corner;
  Vec3 edge_a, edge_b;  ///< perpendicular, non-zero
  /// The four corners in order; std::nullopt unless they form a rectangle (opposite edges equal and adjacent edges
  /// perpendicular to `tolerance` × the edges' lengths, and no edge shorter than 1e-6 of the longest).
  static std::optional<PortalRectangle> from_corners(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, float tolerance = 1e-3f);
  double area_m2() const;
  Vec3 normal() const;  ///< unit, a × b
};

/// The spherical rectangle a portal subtends at a point.
class SphericalRectangle {
 public:
  /// std::nullopt if the point lies in the rectangle's plane (Ω = 0) or the solid angle underflows.
  static std::optional<SphericalRectangle> make(const PortalRectangle& portal, Vec3 origin);
  double solid_angle_sr() const { return solid_angle_sr_; }
  /// A point ON the rectangle, uniform in the solid angle it subtends at the origin, from u ∈ [0,1)².
  Vec3 sample_point(Vec2 u) const;

 private:
  // The local frame (x, y along the edges, z towards the rectangle's plane from the side of the origin flipped so
  // the plane is at z0 < 0) and the quantities of Ureña et al.'s §3.
  double origin_[3], x_[3], y_[3], z_[3];
  double x0_, y0_, z0_, x1_, y1_;
  double b0_, b1_, k_;
  double solid_angle_sr_ = 0;
};

/// True if the ray origin + t·direction, t > 0, meets the rectangle (edges included).
bool passes_through(const PortalRectangle& portal, Vec3 origin, Vec3 direction);

class PortalSet {
 public:
  PortalSet() = default;
  explicit PortalSet(std::vector<PortalRectangle> portals) : portals_(std::move(portals)) {}
  bool empty() const { return portals_.empty(); }
  const std::vector<PortalRectangle>& portals() const { return portals_; }
  double total_area_m2() const;

  struct Sample {
    Vec3 wi;       ///< unit, from the origin through a portal
    float pdf_sr;  ///< pdf(origin, wi), > 0
  };
  /// A direction through the portals as described above, from u ∈ [0,1)² (u.x picks the portal and is reused).
  /// Cost: one spherical-rectangle set-up per portal. std::nullopt where ΣΩ = 0.
  std::optional<Sample> sample(Vec3 origin, Vec2 u) const;
  /// N(origin, wi) / ΣΩ(origin): exactly the density sample() has for wi; 0 when wi misses every portal.
  float pdf(Vec3 origin, Vec3 wi) const;

 private:
  double total_solid_angle(Vec3 origin) const;
  float pdf_given_total(Vec3 origin, Vec3 wi, double total_solid_angle_sr) const;
  std::vector<PortalRectangle> portals_;
};

/// A light at infinity that enters through `portals` as the light tree sees it: each rectangle a two-sided area light
/// (as its two triangles, so the bounds' intensities add up to radiance·A) of `radiance_w_m2_sr`. std::nullopt without
/// portals or radiance: the light is then one of the tree's lights at infinity.
std::optional<LightBounds> portal_light_bounds(const PortalSet& portals, double radiance_w_m2_sr);

}  // namespace rimu
