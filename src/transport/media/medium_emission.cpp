#include "transport/media/medium_emission.h"

#include <array>
#include <cmath>

#include "spectral/spectra/blackbody_spectrum.h"

namespace rimu {

namespace {

// pbrt-v4 emits nothing below this temperature (NanoVDBMedium and GridMedium): cold voxels of a fire's grid.
constexpr float kMinimumTemperatureK = 100.0f;

// B(λ, T) / B(λ_max, T) at four wavelengths: Planck's law over its value at Wien's peak λ_max = b/T.
Float4 peak_normalised_planck(float temperature_k, const SampledWavelengths& lambda) {
  constexpr double kWienB_m_K = 2.897771955e-3;
  const double peak_nm = kWienB_m_K / temperature_k * 1e9;
  const double peak = planck_radiance_w_m2_sr_nm(peak_nm, temperature_k);
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
