// The luminous opening of a goniometric luminaire (IES LM-63's width, length and height): the surface the candela
// table's light leaves from, for lighting near the luminaire (closer than about five times its largest dimension,
// photometry's "five-times rule", the inverse-square law of a point errs by more than ~1 %).
//
// Model (the near-field model of Radiance's ies2rad and of lighting programs): every point of the opening emits with
// the same directional distribution, the radiance towards ω being I(ω) / A⊥(ω), A⊥ the opening's area projected
// along ω, so that far away the luminaire's intensity is I(ω) again. Next-event estimation picks a point p uniformly
// by area (density 1/A) on a face of normal n_f and returns the point-light estimate from p weighted by
//   w(ω) = A · max(0, n_f·ω) / A⊥(ω),
// whose mean over the faces is exactly 1 for every ω (Σ_f A_f max(0, n_f·ω) = A⊥(ω) for a closed convex solid), so
// the illuminance is the point formula averaged over the opening. A flat opening (rectangle, disc) emits from
// both sides with A⊥ = A |n·ω|: w = 1. The opening is not scene geometry: rays do not hit it (like a point light it
// is not seen in mirrors), and shadow rays end on it.
//
// Local frame: x along the C = 0° plane (the file's "length", its 0°-180° axis), y along C = 90° ("width"), z the
// γ = 0 axis (down for a downlight). A flat opening lies in z = 0 at the light's position; a box, vertical cylinder or
// sphere is centred on it.
#pragma once

#include <optional>
#include <string>

#include "transport/geometry/vector.h"

namespace rimu {

class LuminousOpening {
 public:
  enum class Shape { point, rectangle, disc, box, cylinder, sphere };

  LuminousOpening() = default;  ///< a point
  static LuminousOpening rectangle(double length_m, double width_m);
  static LuminousOpening disc(double diameter_m);
  static LuminousOpening box(double length_m, double width_m, double height_m);
  static LuminousOpening cylinder(double diameter_m, double height_m);  ///< axis along z, with its end discs
  static LuminousOpening sphere(double diameter_m);

  Shape shape() const { return shape_; }
  bool is_point() const { return shape_ == Shape::point; }
  const char* name() const;
  double area_m2() const;  ///< the emitting surface (one side of a flat opening)
  /// The area projected along unit local direction w (the silhouette).
  double projected_area_m2(Vec3 w) const;
  /// Half the local bounding box's edges.
  Vec3 half_extent_m() const;

  struct SurfacePoint {
    Vec3 position_m;  ///< local
    Vec3 normal;      ///< local, unit; a flat opening's +z (it emits from both sides)
  };
  /// A point uniform by area from u ∈ [0,1)² (u.x picks the face and is reused).
  SurfacePoint sample(Vec2 u) const;
  /// w(ω) above for a point with `normal` and unit local direction w away from the luminaire.
  double weight(Vec3 normal, Vec3 w) const;

 private:
  Shape shape_ = Shape::point;
  double a_ = 0, b_ = 0, h_ = 0;  // rectangle/box: length (x), width (y), height (z); disc/cylinder/sphere: radius in a_
};

/// LM-63's width, length and height (in the file's units, times `metres_per_unit`) as a shape: all 0 a point;
/// width, length > 0 a rectangle (height 0) or box; width = length < 0 a disc (height 0) or vertical cylinder; all
/// three equal and < 0 a sphere. Other combinations (ellipses, ellipsoids, horizontal cylinders) are not modelled:
/// then no opening, and `error` names the values.
struct LuminousOpeningFromLm63 {
  std::optional<LuminousOpening> opening;
  std::string error;
};
LuminousOpeningFromLm63 luminous_opening_from_lm63(double width, double length, double height, double metres_per_unit);

}  // namespace rimu
