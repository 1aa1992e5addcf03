#include "render/sensors/daylight_factor.h"

#include <algorithm>
#include <cmath>

#include "spectral/error.h"
#include "spectral/photometry/light_units.h"
#include "transport/lights/sky/cie_sky_light.h"

namespace rimu {

double overcast_sky_horizontal_illuminance_lx(const Scene& scene, const TabulatedSpectrum& v, const SourceLocation& where) {
  const CieSkyLight* sky = nullptr;
  for (const auto& light : scene.lights)
    if (!sky) sky = dynamic_cast<const CieSkyLight*>(light.get());
  if (!sky)
    throw InputError(where, "a daylight factor needs a CIE overcast sky: add {\"type\": \"cie_sky\", \"sky_type\": 1, "
                            "\"diffuse_horizontal_illuminance_lx\": 10000} to \"lights\"");
  for (size_t k = 0; k < scene.lights.size(); ++k)
    if (scene.lights[k].get() != sky)
      throw InputError(where, "a daylight factor is measured under a CIE overcast sky alone, but the scene also has " +
                                  scene.light_names[k] + "; remove the other lights (a sun, lamps, emitters)");
  if (sky->type() != 1)
    throw InputError(where, "a daylight factor is defined under the CIE standard overcast sky (sky_type 1), not sky "
                            "type " + std::to_string(sky->type()) + " (" + cie_sky_description(sky->type()) + ")");
  // E_out = L_z ∫ L/L_z cos θ dω, with L_z = K_m Σ S V Δλ of the zenith's spectral radiance (the loader's rule).
  const LightSpectrum& zenith = *sky->emitted_spectrum();
  const double zenith_luminance_nt = zenith.scale() * shape_integrals(*zenith.shape(), v).luminous;
  return zenith_luminance_nt * sky->integrals().cosine_weighted_sr;
}

void check_daylight_factor_grids(const Scene& scene, const SensorSettings& sensors, const TabulatedSpectrum& v,
                                 const std::string& scene_file) {
  for (size_t g = 0; g < sensors.grids.size(); ++g)
    if (sensors.grids[g].daylight_factor)
      overcast_sky_horizontal_illuminance_lx(scene, v,
                                             {scene_file, 0, "/sensors/grids/" + std::to_string(g) + "/daylight_factor"});
}

DaylightFactors daylight_factors(const std::vector<MeterReading>& illuminance_lx, double outdoor_illuminance_lx) {
  DaylightFactors df;
  df.outdoor_illuminance_lx = outdoor_illuminance_lx;
  const double per_lx = 100.0 / outdoor_illuminance_lx;
  double sum = 0.0;
  df.df_min_percent = illuminance_lx.empty() ? 0.0 : INFINITY;
  for (const MeterReading& r : illuminance_lx) {
    const MeterReading p{r.value * per_lx, r.standard_error * per_lx, r.samples};
    df.points_percent.push_back(p);
    sum += p.value;
    df.df_min_percent = std::min(df.df_min_percent, p.value);
    df.df_max_percent = std::max(df.df_max_percent, p.value);
  }
  if (!illuminance_lx.empty()) df.df_avg_percent = sum / double(illuminance_lx.size());
  return df;
}

}  // namespace rimu
