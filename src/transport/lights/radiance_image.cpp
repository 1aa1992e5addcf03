#include "transport/lights/radiance_image.h"

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

namespace {
/// Wavelengths of the midpoint rule: 4 lane groups of 4, 29.4 nm apart (fine for power estimates and weights; the
/// estimate itself never uses it).
constexpr int kIntegralWavelengths = 16;
constexpr double kBandNm = (kLambdaMaxNm - kLambdaMinNm) / kIntegralWavelengths;
static_assert(kIntegralWavelengths == 4 * kLaneCount);
}  // namespace

const std::array<SampledWavelengths, 4>& radiance_integral_wavelengths() {
  const auto group = [](int k) {
    Float4 l;
    for (int j = 0; j < kLaneCount; ++j) l.set(j, float(kLambdaMinNm + (k * kLaneCount + j + 0.5) * kBandNm));
    return SampledWavelengths(l, Float4(float(1.0 / (kLambdaMaxNm - kLambdaMinNm))));
  };
  static const std::array<SampledWavelengths, 4> groups{group(0), group(1), group(2), group(3)};
  return groups;
}

double radiance_integral_band_nm() { return kBandNm; }

double RadianceImage::radiance_integral(int x, int y) const {
  double spectral_sum = 0.0;
  for (const SampledWavelengths& lambda : radiance_integral_wavelengths()) spectral_sum += sum(radiance(x, y, lambda));
  return spectral_sum * kBandNm;
}

void RadianceImage::radiance_integrals(int y, std::span<double> out) const {
  for (int x = 0; x < width(); ++x) out[x] = radiance_integral(x, y);
}

}  // namespace rimu
