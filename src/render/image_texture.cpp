#include "render/image_texture.h"

namespace rimu {

SampledSpectrum ImageTexture::evaluate(Vec2 uv, const SampledWavelengths& lambda) const {
  const Rgb rgb = image_->bilinear(uv);
  const UpsampledReflectance r = upsampler_->upsample_reflectance(rgb);
  return r.spectrum.evaluate(lambda) * Float4(scale_);
}

}  // namespace rimu
