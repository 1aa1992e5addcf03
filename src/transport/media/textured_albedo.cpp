#include "transport/media/textured_albedo.h"

#include <algorithm>
#include <cmath>

#include "spectral/error.h"
#include "transport/media/homogeneous_medium.h"

namespace rimu {

TexturedAlbedo::TexturedAlbedo(SpectralTexturePtr texture, double base_surface_albedo)
    : texture_(std::move(texture)),
      base_single_scattering_albedo_(float(chiang2016_single_scattering_albedo(base_surface_albedo))) {
  if (!texture_) throw InputError({}, "a textured albedo needs a texture");
  if (!(base_single_scattering_albedo_ > 0.0f)) throw InputError({}, "a textured albedo's base albedo must be > 0");
}

SampledSpectrum TexturedAlbedo::scattering_scale(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const SampledSpectrum albedo = texture_->evaluate_at(context, lambda);
  alignas(16) float scale[kLaneCount];
  for (int lane = 0; lane < kLaneCount; ++lane) {
    const float a = std::isfinite(albedo[lane]) ? std::clamp(albedo[lane], 0.0f, 1.0f) : 0.0f;
    scale[lane] = float(chiang2016_single_scattering_albedo(a)) / base_single_scattering_albedo_;
  }
  return Float4::load(scale);
}

}  // namespace rimu
