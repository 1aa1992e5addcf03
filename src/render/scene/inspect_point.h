// Where `rimu-light inspect` observes a light or an IES profile from, and the lamp's electrical power.
#pragma once

#include <optional>

namespace rimu {

struct InspectPoint {
  double distance_m = 1.0;             ///< (0, 1e15] m
  double off_axis_deg = 0.0;           ///< [-180, 180]°
  std::optional<double> electrical_w;  ///< [1e-30, 1e30] W
};

/// Throws InputError naming the option (--distance, --angle, --electrical-watts) for a value outside the ranges
/// above, NaN and infinity included: a report computed from them would print NaN or infinity.
void validate_inspect_point(const InspectPoint& point);

}  // namespace rimu
