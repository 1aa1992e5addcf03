#include "transport/media/homogeneous_medium.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

HomogeneousMedium::HomogeneousMedium(SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m, float g)
    : sigma_a_(std::move(sigma_a_per_m)), sigma_s_(std::move(sigma_s_per_m)), phase_(g) {
  assert(sigma_a_ && sigma_s_);
}

double chiang2016_single_scattering_albedo(double a) {
  a = std::clamp(a, 0.0, 1.0);
  return 1.0 - std::exp(-11.43 * a + 15.38 * a * a - 13.91 * a * a * a);
}

Chiang2016Coefficients chiang2016_coefficients(double surface_albedo, double mean_free_path_m) {
  // 1e-9 m keeps a zero mean free path finite (far below any pixel).
  const double sigma_t = 1.0 / std::max(mean_free_path_m, 1e-9);
  const double albedo = chiang2016_single_scattering_albedo(surface_albedo);
  return {(1.0 - albedo) * sigma_t, albedo * sigma_t};
}

HomogeneousMedium chiang2016_medium(const Spectrum& surface_albedo, const Spectrum& mean_free_path_m, float g) {
  std::vector<double> wavelengths_nm, sigma_a, sigma_s;
  for (int nm = 360; nm <= 830; ++nm) {
    const Chiang2016Coefficients c = chiang2016_coefficients(surface_albedo.value(nm), mean_free_path_m.value(nm));
    wavelengths_nm.push_back(nm);
    sigma_s.push_back(c.sigma_s_per_m);
    sigma_a.push_back(c.sigma_a_per_m);
  }
  auto a = std::make_shared<TabulatedSpectrum>(wavelengths_nm, sigma_a, Extrapolation::clamp, "Chiang 2016 sigma_a");
  auto s = std::make_shared<TabulatedSpectrum>(wavelengths_nm, sigma_s, Extrapolation::clamp, "Chiang 2016 sigma_s");
  return HomogeneousMedium(std::move(a), std::move(s), g);
}

}  // namespace rimu
