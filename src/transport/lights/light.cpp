#include "transport/lights/light.h"

namespace rimu {

SampledSpectrum Light::radiance(const SurfaceHit&, Vec3, const SampledWavelengths&) const { return Float4(0.0f); }

std::optional<LightSample> Light::sample_part_li(int, const LightReference& ref, const SampledWavelengths& lambda,
                                                Vec2 u) const {
  return sample_li(ref, lambda, u);
}

float Light::pdf_part_li(int, const LightReference& ref, Vec3 wi, const SurfaceHit* hit) const {
  return pdf_li(ref, wi, hit);
}

SampledSpectrum Light::radiance_escaped(Vec3, const SampledWavelengths&) const { return Float4(0.0f); }

}  // namespace rimu
