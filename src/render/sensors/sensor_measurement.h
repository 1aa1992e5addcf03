// Measuring a scene's sensors (render/scene/scene_sensors.h) with the integrator that renders its image: lux on
// illuminance grids and meters, nits on luminance meters, each with its Monte Carlo standard error, and the
// statistics EN 12464-1 asks of a grid (Emin, Eavg, Emax, U0 = Emin/Eavg).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <optional>

#include "render/reports/light_meter.h"
#include "render/sensors/daylight_factor.h"
#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

struct SensorMeasureOptions {
  int samples = 256;  ///< per meter point
  /// Independent randomisations the samples are split into (0: replicates_for(samples)). The standard error comes
  /// from the spread of their means: see replicates_for (render/reports/light_meter.h). 1 keeps the whole sequence in one scramble, which is the
  /// more accurate for smooth integrands (a sky through an opening: 2-3× lower error at 32,768 samples than 16
  /// replicates, docs/lighting-validation.md), but then the standard error is the textbook s/√n, which overstates
  /// that error several-fold.
  int replicates = 0;
  uint64_t seed = 1;
  SamplerKind sampler = SamplerKind::sobol;
  int threads = 0;                           ///< 0 = every core
  /// The weighting functions of the extra quantities (SensorSettings::quantities): V'(λ)
  /// (SpectralLibrary::scotopic_v_prime()) and s_mel(λ) (SpectralLibrary::melanopic_action_spectrum()); each must be
  /// given when its quantity is asked for.
  const TabulatedSpectrum* scotopic_v_prime = nullptr;
  const TabulatedSpectrum* melanopic = nullptr;
  /// Polled between points (Ctrl-C: render/interrupt_flag.h); true stops the measurement, which is then incomplete.
  std::function<bool()> stop_requested;
};

/// A grid's readings (index j·count_u + i for cell (i, j)) and its statistics over them, in lx. u0 is 0 when
/// Eavg is 0 (no light reaches the grid).
struct GridReadings {
  std::vector<MeterReading> points;
  /// Scotopic lux and melanopic EDI (lx) of the same points, when SensorSettings::quantities asks for them (else empty).
  std::vector<MeterReading> scotopic_points, melanopic_points;
  double e_min_lx = 0, e_avg_lx = 0, e_max_lx = 0, u0 = 0;
  std::optional<DaylightFactors> daylight_factor;  ///< for a grid with "daylight_factor"
};

struct SensorReadings {
  std::vector<GridReadings> grids;   ///< in the order of SensorSettings::grids
  std::vector<MeterReading> meters;  ///< SensorSettings::points, in lx or nt by their kind
  /// The meters' scotopic (scotopic lx or nt) and melanopic EDI or EDL (lx or nt) readings, when asked for (else empty).
  std::vector<MeterReading> meters_scotopic, meters_melanopic;
  uint64_t discarded_samples = 0;    ///< NaN, infinite or negative estimates, left out of their means (as the film does)
  bool interrupted = false;          ///< stopped by the interrupt: the readings are incomplete
  double seconds = 0;
};


/// Estimates every sensor of `scene` (which must have no participating media and spectral lanes: check_sensor_scene)
/// with `samples` samples per point, split into independent replicates (replicates_for): each sample is one path estimate from the scene's integrator (hero
/// wavelengths as the image's), converted to lux or nits as K_m ∫ V(λ) (·) dλ with K_m = 683 lm/W and `v` the
/// photopic V(λ). The extra quantities weight the same path: scotopic K'_m ∫ V'(λ) (·) dλ (K'_m = 1700 lm/W),
/// melanopic ∫ s_mel(λ) (·) dλ / K_mel,v^D65 (CIE S 026: equivalent daylight (D65) illuminance or luminance). Grids with "daylight_factor" also get their daylight factors (InputError before any sample if the
/// scene has not the one CIE overcast sky they need). The readings depend on the seed and the sample count only, not
/// on the threads. Cost: samples × points paths.
SensorReadings measure_sensors(const Scene& scene, const SensorSettings& sensors, const TabulatedSpectrum& v,
                               const SensorMeasureOptions& options);

/// InputError naming `where` if `scene`'s sensors cannot be measured: participating media (the volumetric
/// integrator has no receptor yet), rgb transport (its lanes are not wavelengths).
void check_sensor_scene(const Scene& scene, const std::string& where);

}  // namespace rimu
