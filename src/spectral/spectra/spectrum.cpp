#include "spectral/spectra/spectrum.h"

#include <sstream>

namespace rimu {

SampledSpectrum Spectrum::sample(const SampledWavelengths& lambda) const {
  const auto l = lambda.lambda_nm().to_array();
  return Float4(float(value(l[0])), float(value(l[1])), float(value(l[2])), float(value(l[3])));
}

std::string ConstantSpectrum::describe() const {
  std::ostringstream out;
  out << "constant " << value_;
  return out.str();
}

}  // namespace rimu
