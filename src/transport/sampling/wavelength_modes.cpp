#include "transport/sampling/wavelength_modes.h"

namespace rimu {

SampledWavelengths rgb_transport_lanes() {
  // Dominant wavelengths of the sRGB primaries against D65 are about 612, 549 and 465 nm (from the primaries'
  // chromaticities, IEC 61966-2-1); they matter only for inputs left spectral, which are point-sampled there.
  return SampledWavelengths(Float4(612.0f, 549.0f, 465.0f, 549.0f), Float4(0.25f, 0.25f, 0.25f, 0.0f));
}

SampledWavelengths sample_path_wavelengths(WavelengthMode mode, Sampler& sampler,
                                          const TabulatedWavelengthDensity* density) {
  switch (mode) {
    case WavelengthMode::hero:
    case WavelengthMode::single:
      return density ? density->sample_wavelengths(sampler.next_1d())
                     : SampledWavelengths::sample_visible(sampler.next_1d());
    case WavelengthMode::independent: {
      alignas(16) float lambda_nm[kLaneCount], pdf[kLaneCount];
      for (int lane = 0; lane < kLaneCount; ++lane) {
        const float u = sampler.next_1d();
        lambda_nm[lane] = density ? density->sample(u) : sample_visible_wavelength(u);
        pdf[lane] = density ? density->pdf(lambda_nm[lane]) : visible_wavelength_pdf(lambda_nm[lane]);
      }
      return SampledWavelengths(Float4::load(lambda_nm), Float4::load(pdf));
    }
    case WavelengthMode::rgb:
      (void)sampler.next_1d();
      return rgb_transport_lanes();
  }
  return SampledWavelengths::sample_visible(sampler.next_1d());
}

std::optional<WavelengthMode> parse_wavelength_mode(std::string_view name) {
  if (name == "hero") return WavelengthMode::hero;
  if (name == "single") return WavelengthMode::single;
  if (name == "independent") return WavelengthMode::independent;
  if (name == "rgb") return WavelengthMode::rgb;
  return std::nullopt;
}

const char* wavelength_mode_name(WavelengthMode mode) {
  switch (mode) {
    case WavelengthMode::hero: return "hero";
    case WavelengthMode::single: return "single";
    case WavelengthMode::independent: return "independent";
    case WavelengthMode::rgb: return "rgb";
  }
  return "hero";
}

}  // namespace rimu
