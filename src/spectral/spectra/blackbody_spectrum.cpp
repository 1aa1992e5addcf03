#include "spectral/spectra/blackbody_spectrum.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "spectral/error.h"

namespace rimu {

double planck_radiance_w_m2_sr_nm(double lambda_nm, double temperature_k) {
  if (!(lambda_nm > 0.0) || !(temperature_k > 0.0)) return 0.0;
  const double lambda_m = lambda_nm * 1e-9;
  const double c1 = 2.0 * kPlanckConstant_Js * kSpeedOfLight_m_s * kSpeedOfLight_m_s;  // W·m²/sr
  const double c2 = kPlanckConstant_Js * kSpeedOfLight_m_s / kBoltzmannConstant_J_K;   // m·K
  // expm1 keeps precision at long wavelengths/high temperatures where the exponent is tiny.
  const double per_metre = c1 / std::pow(lambda_m, 5) / std::expm1(c2 / (lambda_m * temperature_k));
  return per_metre * 1e-9;
}

double planck_peak_radiance_w_m2_sr_nm(double temperature_k) {
  return planck_radiance_w_m2_sr_nm(kWienDisplacement_m_K / temperature_k * 1e9, temperature_k);
}

BlackbodySpectrum::BlackbodySpectrum(double temperature_k, Scale scale) : temperature_k_(temperature_k), scale_(1.0) {
  if (!(temperature_k > 0.0 && temperature_k <= 1e6)) {
    std::ostringstream message;  // %g-style: std::to_string spells 1e308 with 309 digits
    message << "blackbody temperature must be a finite number in (0, 1e6] K, got " << temperature_k;
    throw InputError({}, message.str());
  }
  if (scale == Scale::peak_one) scale_ = 1.0 / planck_peak_radiance_w_m2_sr_nm(temperature_k);
}

double BlackbodySpectrum::value(double lambda_nm) const {
  return scale_ * planck_radiance_w_m2_sr_nm(lambda_nm, temperature_k_);
}

double BlackbodySpectrum::max_value() const {
  const double peak_nm = std::clamp(kWienDisplacement_m_K / temperature_k_ * 1e9, 360.0, 830.0);
  return value(peak_nm);
}

std::string BlackbodySpectrum::describe() const {
  std::ostringstream out;
  out << "blackbody " << temperature_k_ << " K";
  return out.str();
}

}  // namespace rimu
