// A subsurface medium's surface albedo that varies over its boundary: Chiang et al. 2016's inputs with a texture.
#pragma once

#include "transport/textures/spectral_texture.h"

namespace rimu {

/// Chiang et al. 2016 fix σ_t = 1/d by the mean free path alone; the surface albedo A sets only the single-scattering
/// albedo α(A) = σ_s/σ_t (homogeneous_medium.h). A texture of A over the boundary therefore changes σ_s alone, by the
/// factor r(λ) = α(A(λ))/α₀ against the medium built for a uniform A₀ (its σ_t and the distances it samples stay
/// as they are). The integrator reads r where a path enters the medium (the texture at the entry point's uv, as
/// pbrt-v4 reads its BSSRDF's albedo at the entry point) and multiplies its throughput by r at each scattering event
/// in that medium: unbiased for any distance sampling, since σ_s enters the estimator only as that weight (with null-
/// collision tracking, the scatter probability is a sampling choice, which σ_s ≠ 0 keeps valid).
class TexturedAlbedo {
 public:
  /// The medium of `texture` was built for the uniform surface albedo `base_surface_albedo` ∈ (0, 1].
  TexturedAlbedo(SpectralTexturePtr texture, double base_surface_albedo);
  /// r(λ) = α(A(λ))/α₀ at a point of the boundary (A clamped to [0, 1] per lane).
  SampledSpectrum scattering_scale(const MaterialContext& context, const SampledWavelengths& lambda) const;

 private:
  SpectralTexturePtr texture_;
  float base_single_scattering_albedo_;
};

}  // namespace rimu
