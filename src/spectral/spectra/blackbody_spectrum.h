// Planck's law.
#pragma once

#include "spectral/spectra/spectrum.h"

namespace rimu {

/// SI 2019 exact constants.
inline constexpr double kPlanckConstant_Js = 6.62607015e-34;
inline constexpr double kSpeedOfLight_m_s = 299792458.0;
inline constexpr double kBoltzmannConstant_J_K = 1.380649e-23;

/// Spectral radiance of a black body at `temperature_k`, in W/(m²·sr·nm):
/// L(λ,T) = 2hc²/λ⁵ / (exp(hc/(λ k T)) − 1), with λ in metres, times 1e-9 m/nm.
double planck_radiance_w_m2_sr_nm(double lambda_nm, double temperature_k);

/// Wien's displacement constant b: a black body's spectral radiance peaks at λ = b/T.
inline constexpr double kWienDisplacement_m_K = 2.897771955e-3;

/// The spectral radiance at that peak, W/(m²·sr·nm): what a peak-normalised black body is divided by.
double planck_peak_radiance_w_m2_sr_nm(double temperature_k);

/// A black body. Absolute (W/(m²·sr·nm)) or scaled so its peak (Wien's law) is 1, as a light's shape.
class BlackbodySpectrum final : public Spectrum {
 public:
  enum class Scale { absolute_radiance, peak_one };
  /// Throws InputError unless 0 < temperature_k <= 1e6 and finite.
  BlackbodySpectrum(double temperature_k, Scale scale);

  double value(double lambda_nm) const override;
  double max_value() const override;
  std::string describe() const override;
  double temperature_k() const { return temperature_k_; }

 private:
  double temperature_k_;
  double scale_;
};

}  // namespace rimu
