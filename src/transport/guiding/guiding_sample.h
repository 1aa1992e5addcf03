// What path guiding learns from: one record per path vertex, written by PathGuidingRecord and read by the fits of
// the directional quadtree and of the vMF mixture (guiding_field.h builds both from the same records, in place).
#pragma once

#include <cmath>

#include "transport/geometry/vector.h"

namespace rimu {

/// One recorded direction: where it lies on the equal-area square and what it brought (incident luminance divided
/// by the density it was sampled with: an estimate of that direction's share of the incident flux).
struct DirectionalSample {
  Vec2 square;
  float weight = 0.0f;
};

/// One path vertex's record: where it was, which way its surface faced (facing_of), the direction the path left it
/// by (on the equal-area square) and the incident luminance that direction brought divided by the density it was
/// sampled with.
struct GuidingSample {
  Vec3 position;
  DirectionalSample direction;
  int facing = 0;
  /// To the next vertex along the direction: the mixture's parallax (∞: none, or not recorded: quadtree fields).
  float distance = INFINITY;
};

}  // namespace rimu
