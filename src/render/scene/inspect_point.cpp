#include "render/scene/inspect_point.h"

#include <sstream>

#include "spectral/error.h"
#include "spectral/photometry/light_units.h"

namespace rimu {
namespace {

[[noreturn]] void refuse(const char* option, const char* expected, double got) {
  std::ostringstream message;
  message << "expected " << expected << "; got " << got;
  throw InputError({"", 0, option}, message.str());
}

}  // namespace

void validate_inspect_point(const InspectPoint& point) {
  // 1e15 m (a thousand times Sun-Neptune) keeps I/d² far from underflowing to a printed 0 for any valid amount.
  if (!(point.distance_m > 0.0 && point.distance_m <= 1e15))
    refuse("--distance", "a distance in (0, 1e15] m", point.distance_m);
  if (!(point.off_axis_deg >= -180.0 && point.off_axis_deg <= 180.0))
    refuse("--angle", "an angle off the axis in [-180, 180] degrees", point.off_axis_deg);
  if (point.electrical_w && !(*point.electrical_w >= kMinLightAmount && *point.electrical_w <= kMaxLightAmount))
    refuse("--electrical-watts", "the lamp's electrical power in [1e-30, 1e30] W", *point.electrical_w);
}

}  // namespace rimu
