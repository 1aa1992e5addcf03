// A spectral quantity that varies over a surface: the input side of materials.
#pragma once

#include <memory>

#include "spectral/spectra/spectrum.h"
#include "transport/textures/material_context.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// A spectrum per surface point, looked up by texture coordinates at the path's wavelengths.
/// Implementations are immutable after construction and safe to call from many threads.
class SpectralTexture {
 public:
  virtual ~SpectralTexture() = default;
  /// The values at `uv` and the four sampled wavelengths (per-sample path: no allocation).
  virtual SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const = 0;
  /// The values at a surface point: what materials call. Textures that depend on more than uv (the normal, wo)
  /// override this; the default looks up `context.uv`.
  virtual SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const {
    return evaluate(context.uv, lambda);
  }
  /// The value averaged over a footprint at `st` spanned by (∂s/∂x, ∂t/∂x) and (∂s/∂y, ∂t/∂y): what a filtered
  /// image texture answers (render/image/mip_pyramid.h). The default ignores the footprint.
  virtual SampledSpectrum evaluate_footprint(Vec2 st, Vec2 /*dst_dx*/, Vec2 /*dst_dy*/,
                                             const SampledWavelengths& lambda) const {
    return evaluate(st, lambda);
  }
};

using SpectralTexturePtr = std::shared_ptr<const SpectralTexture>;

/// The same spectrum everywhere.
class ConstantSpectralTexture final : public SpectralTexture {
 public:
  explicit ConstantSpectralTexture(SpectrumPtr spectrum) : spectrum_(std::move(spectrum)) {}
  SampledSpectrum evaluate(Vec2, const SampledWavelengths& lambda) const override {
    return spectrum_->sample(lambda);
  }
  // Overridden too so that a material's lookup is one virtual call, not two (the default forwards to evaluate).
  SampledSpectrum evaluate_at(const MaterialContext&, const SampledWavelengths& lambda) const override {
    return spectrum_->sample(lambda);
  }
  const SpectrumPtr& spectrum() const { return spectrum_; }

 private:
  SpectrumPtr spectrum_;
};

}  // namespace rimu
