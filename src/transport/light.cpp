#include "transport/light.h"

namespace rimu {

SampledSpectrum Light::radiance(const SurfaceHit&, Vec3, const SampledWavelengths&) const { return Float4(0.0f); }

SampledSpectrum Light::radiance_escaped(Vec3, const SampledWavelengths&) const { return Float4(0.0f); }

}  // namespace rimu
