// A ray: origin, unit direction, and the interval it is tested over.
#pragma once

#include <limits>

#include "transport/geometry/vector.h"

namespace rimu {

struct Ray {
  Vec3 origin;
  Vec3 direction;  ///< unit length
  float t_min = 0.0f;
  float t_max = std::numeric_limits<float>::infinity();
};

}  // namespace rimu
