// The daylight factor of an illuminance grid: DF = E_in / E_out × 100 %, the illuminance at a point inside over the
// horizontal illuminance an unobstructed point outside receives from the same sky, under the CIE standard overcast
// sky (CIE S 011/E:2003 type 1; its luminance depends on the elevation only, so DF does not depend on the hour or
// the orientation of the building). E_out is not measured: it is the sky's own calibration, the zenith luminance
// times ∫ L/L_z cos θ dω over the hemisphere (transport/lights/sky/cie_sky_light.h), exact to the sky's quadrature
// (≤ 1e-5 relative). A point's standard error in DF is its illuminance's, over E_out.
#pragma once

#include <string>
#include <vector>

#include "render/reports/light_meter.h"
#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

/// E_out in lx: the unobstructed horizontal illuminance of the scene's CIE overcast sky. InputError at `where` (the
/// grid's "daylight_factor" key) unless the scene's lights are exactly one "cie_sky" of sky_type 1: a daylight
/// factor is defined under that sky alone (a sun or a lamp would count in E_in but not in E_out). `v` is V(λ).
double overcast_sky_horizontal_illuminance_lx(const Scene& scene, const TabulatedSpectrum& v, const SourceLocation& where);

/// Checks every grid with "daylight_factor" against the scene (the call above), naming `scene_file` and
/// /sensors/grids/<index>/daylight_factor. A render job calls it before measuring anything.
void check_daylight_factor_grids(const Scene& scene, const SensorSettings& sensors, const TabulatedSpectrum& v,
                                 const std::string& scene_file);

/// A grid's daylight factors in %, from its illuminance readings and E_out: each point's value and standard error
/// scaled by 100 / E_out, and the grid's minimum, mean and maximum.
struct DaylightFactors {
  double outdoor_illuminance_lx = 0;
  std::vector<MeterReading> points_percent;
  double df_min_percent = 0, df_avg_percent = 0, df_max_percent = 0;
};
DaylightFactors daylight_factors(const std::vector<MeterReading>& illuminance_lx, double outdoor_illuminance_lx);

}  // namespace rimu
