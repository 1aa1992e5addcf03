#include "transport/emission_wavelength_density.h"

#include <cmath>

#include "spectral/wavelength_range.h"

namespace rimu {

TabulatedWavelengthDensity emission_wavelength_density(const std::vector<std::unique_ptr<Light>>& lights,
                                                       const LightSampler& light_sampler, const Observer& response,
                                                       double defensive_fraction) {
  struct Term {
    const Spectrum* shape;  // nullptr: flat
    double weight;          // Pᵢ / ∫sᵢ (or Pᵢ / 470 nm for a flat term)
  };
  std::vector<Term> terms;
  constexpr double kRangeNm = kLambdaMaxNm - kLambdaMinNm;
  for (size_t i = 0; i < lights.size(); ++i) {
    const double probability = light_sampler.probability(int(i));
    if (!(probability > 0.0)) continue;
    const Spectrum* shape = lights[i]->emitted_spectrum_shape();
    double integral = 0.0;
    if (shape) {
      // The trapezoid rule at 1 nm, as LightSpectrum::integral_360_830.
      for (int nm = int(kLambdaMinNm); nm <= int(kLambdaMaxNm); ++nm)
        integral += (nm == int(kLambdaMinNm) || nm == int(kLambdaMaxNm) ? 0.5 : 1.0) * shape->value(nm);
    }
    if (shape && integral > 0.0 && std::isfinite(integral)) terms.push_back({shape, probability / integral});
    else terms.push_back({nullptr, probability / kRangeNm});
  }
  return light_weighted_wavelength_density(
      [&](double nm) {
        double s = 0.0;
        for (const Term& t : terms) s += t.weight * (t.shape ? t.shape->value(nm) : 1.0);
        return s;
      },
      response, defensive_fraction);
}

}  // namespace rimu
