#include "spectral/colorimetry/tristimulus_method.h"

#include <cmath>

#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

std::string_view method_name(TristimulusMethod method) {
  switch (method) {
    case TristimulusMethod::native: return "native";
    case TristimulusMethod::interpolate_1nm: return "1nm";
    case TristimulusMethod::astm_e308: return "astm-e308";
  }
  return "?";
}

std::optional<TristimulusMethod> parse_tristimulus_method(std::string_view text) {
  for (TristimulusMethod m : {TristimulusMethod::native, TristimulusMethod::interpolate_1nm, TristimulusMethod::astm_e308})
    if (text == method_name(m)) return m;
  return std::nullopt;
}

std::optional<double> uniform_interval_nm(const TabulatedSpectrum& spectrum) {
  const auto& lambda = spectrum.wavelengths_nm();
  const double step = lambda[1] - lambda[0];
  for (size_t i = 1; i < lambda.size(); ++i)
    if (std::abs((lambda[i] - lambda[i - 1]) - step) > 1e-6) return std::nullopt;
  return step;
}

TristimulusMethod default_tristimulus_method(const TabulatedSpectrum& spectrum) {
  const std::optional<double> step = uniform_interval_nm(spectrum);
  if (!step) return TristimulusMethod::interpolate_1nm;
  if (std::abs(*step - 1.0) < 1e-6 || std::abs(*step - 5.0) < 1e-6) return TristimulusMethod::native;
  if (std::abs(*step - 10.0) < 1e-6 || std::abs(*step - 20.0) < 1e-6) return TristimulusMethod::astm_e308;
  return TristimulusMethod::interpolate_1nm;
}

}  // namespace rimu
