#include "transport/lights/radiance_image.h"

#include <vector>

#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

namespace {
/// Wavelengths of the midpoint rule: 4 lane groups of 4, 29.4 nm apart (fine for power estimates and weights; the
/// estimate itself never uses it).
constexpr int kIntegralWavelengths = 16;
constexpr double kBandNm = (kLambdaMaxNm - kLambdaMinNm) / kIntegralWavelengths;

std::vector<SampledWavelengths> midpoint_groups() {
  std::vector<SampledWavelengths> groups;
  for (int g = 0; g < kIntegralWavelengths / kLaneCount; ++g) {
    Float4 l;
    for (int j = 0; j < kLaneCount; ++j) l.set(j, float(kLambdaMinNm + (g * kLaneCount + j + 0.5) * kBandNm));
    groups.emplace_back(l, Float4(float(1.0 / (kLambdaMaxNm - kLambdaMinNm))));
  }
  return groups;
}
}  // namespace

double pixel_radiance_integral(const RadianceImage& image, int x, int y) {
  static const auto groups = midpoint_groups();
  double spectral_sum = 0.0;
  for (const auto& lambda : groups) spectral_sum += sum(image.radiance(x, y, lambda));
  return spectral_sum * kBandNm;
}

}  // namespace rimu
