#include "render/scene/hair_absorption.h"

#include <string>
#include <vector>

#include "spectral/spectra/tabulated_spectrum.h"
#include "spectral/upsampling/sigmoid_polynomial.h"

namespace rimu {

SpectrumPtr melanin_sigma_a(SpectralLibrary& library, double eumelanin, double pheomelanin) {
  // pbrt-v4 mixes the pigments in RGB and upsamples the sum once (HairBxDF::SigmaAFromConcentration); fitting
  // each pigment and adding the spectra would differ slightly for mixtures, since the fit is not linear.
  const Rgb rgb{0.419 * eumelanin + 0.187 * pheomelanin, 0.697 * eumelanin + 0.4 * pheomelanin,
                1.37 * eumelanin + 1.05 * pheomelanin};
  const SigmoidFitter fitter(library, RgbColourSpace::named("srgb-linear"));
  const SigmoidSpectrum fit = fitter.fit_unbounded(rgb);
  std::vector<double> nm, values;
  for (int wavelength_nm = 360; wavelength_nm <= 830; ++wavelength_nm) {
    nm.push_back(wavelength_nm);
    values.push_back(fit.value(wavelength_nm));
  }
  return std::make_shared<TabulatedSpectrum>(std::move(nm), std::move(values), Extrapolation::clamp,
                                             "hair melanin σa (eumelanin " + std::to_string(eumelanin) +
                                                 ", pheomelanin " + std::to_string(pheomelanin) + ")");
}

}  // namespace rimu
