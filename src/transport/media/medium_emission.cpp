#include "transport/media/medium_emission.h"

#include <array>
#include <cmath>

#include "spectral/spectra/blackbody_spectrum.h"

namespace rimu {

namespace {

// pbrt-v4 emits nothing below this temperature (NanoVDBMedium and GridMedium): cold voxels of a fire's grid.
constexpr float kMinimumTemperatureK = 100.0f;

// B(λ, T) / B(λ_max, T) at four wavelengths, as BlackbodySpectrum's peak_one scale (without its 1e6 K input bound:
// a grid's temperatures are not user input checked at load).
Float4 peak_normalised_planck(float temperature_k, const SampledWavelengths& lambda) {
  const double peak = planck_peak_radiance_w_m2_sr_nm(temperature_k);
  std::array<float, kLaneCount> out{};
  for (int k = 0; k < kLaneCount; ++k)
    out[size_t(k)] = float(planck_radiance_w_m2_sr_nm(lambda.lambda_nm(k), temperature_k) / peak);
  return Float4::load(out.data());
}

}  // namespace

MediumEmission::MediumEmission(std::shared_ptr<const GridMedium> temperature, double offset_k, double temperature_scale,
                               double scale)
    : temperature_(std::move(temperature)),
      offset_k_(float(offset_k)),
      temperature_scale_(float(temperature_scale)),
      scale_(float(scale)) {}

SampledSpectrum MediumEmission::radiance_at(Vec3 p, const SampledWavelengths& lambda) const {
  if (shape_) return shape_->sample(lambda) * Float4(scale_);
  const float t = (temperature_->density(p) - offset_k_) * temperature_scale_;
  if (!(t > kMinimumTemperatureK) || !std::isfinite(t)) return Float4(0.0f);
  return peak_normalised_planck(t, lambda) * Float4(scale_);
}

}  // namespace rimu
