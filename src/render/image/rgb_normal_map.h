// A tangent-space normal map from an RGB image (pbrt-v4's "normalmap" convention).
#pragma once

#include <memory>

#include "render/image/rgb_image.h"
#include "transport/textures/shading_normal_map.h"

namespace rimu {

/// n = 2·rgb − 1 per texel, looked up bilinearly (RgbImage::bilinear: coordinates repeating, v = 0 the bottom row,
/// which is pbrt-v4's lookup at (u, 1 − v) into an image whose row 0 is the top). The image is normally read with
/// linear encoding (pbrt-v4 asks for normal maps so: an 8-bit value v stands for v/255, no sRGB curve); a scene may
/// ask for the sRGB curve, as the pbrt importer does for the 8-bit files pbrt-v4's reader decodes so anyway.
class RgbNormalMap final : public TangentNormalTexture {
 public:
  explicit RgbNormalMap(std::shared_ptr<const RgbImage> image) : image_(std::move(image)) {}
  Vec3 evaluate(Vec2 uv) const override {
    const Rgb c = image_->bilinear(uv);
    return {float(2.0 * c.r - 1.0), float(2.0 * c.g - 1.0), float(2.0 * c.b - 1.0)};
  }

 private:
  std::shared_ptr<const RgbImage> image_;
};

}  // namespace rimu
