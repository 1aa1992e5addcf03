#include "render/image_texture.h"

namespace rimu {

SampledSpectrum ImageTexture::evaluate(Vec2 uv, const SampledWavelengths& lambda) const {
  const Rgb rgb = image_->bilinear(uv);
  return upsampler_->reflectance_spectrum(rgb).evaluate(lambda) * Float4(scale_);
}

}  // namespace rimu
