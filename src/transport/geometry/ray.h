// A ray: origin, unit direction, the interval it is tested over, and the moment it is traced at.
#pragma once

#include <limits>

#include "transport/geometry/vector.h"

namespace rimu {

struct Ray {
  Vec3 origin;
  Vec3 direction;  ///< unit length
  float t_min = 0.0f;
  float t_max = std::numeric_limits<float>::infinity();
  /// When, within the shutter (0 = open, 1 = close), the ray is traced: it sees moving objects where they are at
  /// that moment (motion blur). Every ray of a camera sample's path carries the camera ray's time.
  float time = 0.0f;
};

}  // namespace rimu
