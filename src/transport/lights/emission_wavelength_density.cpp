#include "transport/lights/emission_wavelength_density.h"
#include "spectral/colorimetry/light_weighted_wavelength_density.h"

#include <cmath>

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

TabulatedWavelengthDensity emission_wavelength_density(const std::vector<std::unique_ptr<Light>>& lights,
                                                       const PowerLightSampler& light_sampler, const Observer& response,
                                                       double defensive_fraction) {
  struct Term {
    const LightSpectrum* spectrum;  // nullptr: flat
    double weight;                  // Pᵢ / ∫ spectrum (or Pᵢ / 470 nm for a flat term)
  };
  std::vector<Term> terms;
  constexpr double kRangeNm = kLambdaMaxNm - kLambdaMinNm;
  for (size_t i = 0; i < lights.size(); ++i) {
    const double probability = light_sampler.probability(int(i));
    if (!(probability > 0.0)) continue;
    const LightSpectrum* spectrum = lights[i]->emitted_spectrum();
    const double integral = spectrum ? spectrum->integral_360_830() : 0.0;
    if (integral > 0.0 && std::isfinite(integral)) terms.push_back({spectrum, probability / integral});
    else terms.push_back({nullptr, probability / kRangeNm});
  }
  return light_weighted_wavelength_density(
      [&](double nm) {
        double s = 0.0;
        for (const Term& t : terms) s += t.weight * (t.spectrum ? t.spectrum->value(nm) : 1.0);
        return s;
      },
      response, defensive_fraction);
}

}  // namespace rimu
