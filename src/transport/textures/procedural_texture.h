// pbrt-v4's procedural textures: noise sums (fbm, wrinkled, windy), polka dots and marble.
#pragma once

#include <memory>
#include <vector>

#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "transport/textures/float_texture.h"
#include "transport/textures/spectral_texture_ops.h"

namespace rimu {

/// The parameters of a noise sum: `octaves` (0-30) of gradient noise, each 1.99× the frequency of the last and
/// `roughness` (ω, |ω| ≤ 10) times its weight.
struct NoiseOctaves {
  int octaves = 8;
  float roughness = 0.5f;
};

/// A float texture of noise at the texture-space point (transport/textures/perlin_noise.h), point-sampled with every octave:
///   fbm:      fbm(p, ω, octaves), in about [−1, 1], mean 0;
///   wrinkled: turbulence(p, ω, octaves), ≥ 0;
///   windy:    |fbm(p/10, 0.5, 3)| · fbm(p, 0.5, 6) (waves whose height a slower noise modulates; no parameters).
/// Throws InputError if octaves is outside 0-30 or |roughness| > 10.
class NoiseFloatTexture final : public FloatTexture {
 public:
  enum class Kind { fbm, wrinkled, windy };
  NoiseFloatTexture(Kind kind, NoiseOctaves octaves, const Transform& texture_from_world);
  float evaluate(const MaterialContext& context) const override;

 private:
  Kind kind_;
  NoiseOctaves octaves_;
  Transform texture_from_world_;
};

/// `inside` on pbrt-v4's polka dots of the mapped (s, t) (inside_polka_dot), `outside` elsewhere.
class DotsFloatTexture final : public FloatTexture {
 public:
  DotsFloatTexture(FloatTexturePtr inside, FloatTexturePtr outside, TextureMapping mapping);
  float evaluate(const MaterialContext& context) const override;

 private:
  FloatTexturePtr inside_, outside_;
  TextureMapping mapping_;
};

/// The same with spectral textures.
class DotsSpectralTexture final : public SpectralTextureAtPoint {
 public:
  DotsSpectralTexture(SpectralTexturePtr inside, SpectralTexturePtr outside, TextureMapping mapping);
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override;

 private:
  SpectralTexturePtr inside_, outside_;
  TextureMapping mapping_;
};

/// pbrt-v4's marble: at the texture-space point p scaled by `scale`, t = ½ + ½·sin(p_y + variation·fbm(p, ω,
/// octaves)) picks a colour on a fixed grey-and-slate ramp (marble_colour).
struct MarbleParameters {
  NoiseOctaves noise;
  float scale = 1.0f;
  float variation = 0.2f;
};

/// The ramp position t ∈ [0, 1] of marble at texture-space point p.
float marble_ramp_position(Vec3 p, const MarbleParameters& parameters);
/// The ramp's colour at t ∈ [0, 1], linear sRGB: 1.5 × a cubic Bézier spline through pbrt-v4's nine control colours
/// (six overlapping segments of four points, t split evenly between them). Every channel is within [0.3, 0.9].
Rgb marble_colour(float t);

/// Marble as a reflectance. The ramp is upsampled once, at construction, at kMarbleRampSize evenly spaced t
/// (RgbUpsampler::reflectance_coefficients of linear sRGB), and a lookup blends the two nearest entries' spectra:
/// the colour between entries is their linear blend (the ramp's curvature over 1/1023 of t is below 10⁻⁵ of its
/// value). Without an upsampler (rgb transport) the lanes carry the linear sRGB itself (lanes 0-2, lane 3 = G).
class MarbleSpectralTexture final : public SpectralTextureAtPoint {
 public:
  static constexpr int kMarbleRampSize = 1024;
  /// `upsampler` must be linear sRGB's (or null for rgb transport). Throws InputError if octaves is outside 0-30
  /// or scale/variation are not finite.
  MarbleSpectralTexture(MarbleParameters parameters, const Transform& texture_from_world,
                        std::shared_ptr<const RgbUpsampler> upsampler);
  SampledSpectrum evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const override;

 private:
  MarbleParameters parameters_;
  Transform texture_from_world_;
  std::shared_ptr<const RgbUpsampler> upsampler_;
  std::vector<BasisCoefficients> ramp_;  // spectral mode
  std::vector<Rgb> ramp_rgb_;            // rgb transport
};

}  // namespace rimu
