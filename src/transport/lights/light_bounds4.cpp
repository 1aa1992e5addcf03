#include "transport/lights/light_bounds4.h"

#include <algorithm>
#include <cmath>


namespace rimu {

void ImportanceBounds4::set(int lane, const ImportanceBounds& b) {
  const auto i = size_t(lane);
  centre_x[i] = b.centre_m.x, centre_y[i] = b.centre_m.y, centre_z[i] = b.centre_m.z;
  half_x[i] = b.half_m.x, half_y[i] = b.half_m.y, half_z[i] = b.half_m.z;
  radius2_m2[i] = b.radius2_m2, radius_m[i] = b.radius_m;
  axis_x[i] = b.axis.x, axis_y[i] = b.axis.y, axis_z[i] = b.axis.z;
  cos_theta_o[i] = b.cos_theta_o, sin_theta_o[i] = b.sin_theta_o, cos_theta_e[i] = b.cos_theta_e;
  intensity_w_sr[i] = b.intensity_w_sr, plane_offset_m[i] = b.plane_offset_m;
  certify_threshold[i] = 3.0f;
  if (!b.two_sided && b.cos_theta_lit < kLitConeCosMargin)
    certify_threshold[i] = b.cos_theta_lit * kLitConeCosMargin +
                           std::sqrt(std::max(0.0f, 1.0f - b.cos_theta_lit * b.cos_theta_lit)) * kLitConeSinMargin;
  two_sided[i] = b.two_sided ? ~0u : 0u;
  half_space[i] = b.half_space ? ~0u : 0u;
}

}  // namespace rimu
