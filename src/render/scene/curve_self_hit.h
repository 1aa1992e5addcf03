// The second rule by which a ray leaving a fibre passes through it (the first is is_self_hit, curve_set.h).
#pragma once

#include <cstdint>

#include "render/scene/curve_set.h"

namespace rimu {

/// Whether a candidate hit at distance `ray_t` on cylinder segment `segment` at t leaves the tube: the hit's offset
/// from the axis, made perpendicular to it, points along the ray, so the ray started inside the tube. Such a ray was
/// transmitted into this fibre, whose BSDF accounts for the fibre whole: it must pass through the far side however
/// far along the fibre that lies (beyond is_self_hit's four radii when it runs nearly along the axis). False for
/// flat curves and ribbons, which have no inside.
bool leaves_cylinder(const CurveSet& set, uint32_t segment, float t, Vec3 ray_origin, Vec3 ray_direction, float ray_t);

}  // namespace rimu
