// A spectral quantity that varies over a surface: the input side of materials.
#pragma once

#include <memory>

#include "spectral/spectrum.h"
#include "transport/vector.h"

namespace rimu {

/// A spectrum per surface point, looked up by texture coordinates at the path's wavelengths.
/// Implementations are immutable after construction and safe to call from many threads.
class SpectralTexture {
 public:
  virtual ~SpectralTexture() = default;
  /// The values at `uv` and the four sampled wavelengths (per-sample path: no allocation).
  virtual SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const = 0;
};

using SpectralTexturePtr = std::shared_ptr<const SpectralTexture>;

/// The same spectrum everywhere.
class ConstantSpectralTexture final : public SpectralTexture {
 public:
  explicit ConstantSpectralTexture(SpectrumPtr spectrum) : spectrum_(std::move(spectrum)) {}
  SampledSpectrum evaluate(Vec2, const SampledWavelengths& lambda) const override {
    return spectrum_->sample(lambda);
  }
  const SpectrumPtr& spectrum() const { return spectrum_; }

 private:
  SpectrumPtr spectrum_;
};

}  // namespace rimu
