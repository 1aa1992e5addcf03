// The inputs of the rgb transport baseline (WavelengthMode::rgb): every spectral input replaced at load by an RGB.
//
// RGB transport exists to measure what it gets wrong (issue 7; docs/benchmarks.md), so the conversion is the one an
// RGB renderer's user would make, done once at load and never in the per-sample loop:
//   reflectance: its CIE 1931 XYZ under D65 (CIE 15:2004 eq. 7.2), to linear sRGB (IEC 61966-2-1 matrix), divided
//                channel by channel by the perfect diffuser's, so ρ = 1 is exactly (1, 1, 1); clipped to [0, 1];
//   emission:    its film XYZ (∫ S cₖ dλ with the film's normalised colour-matching functions, render/film/film.h), to
//                linear sRGB, negative channels (outside the sRGB gamut) clipped to 0: a light seen directly gives
//                the same film XYZ as in spectral mode whenever it is inside the gamut;
//   IOR:         its value at 550 nm in every lane, so nothing disperses;
//   coefficient: (a medium's σ_a, σ_s) converted like a reflectance but not clipped above, so a constant c is
//                exactly (c, c, c): the D65-weighted band averages an RGB renderer's user would type in;
//   Chiang 2016 albedo and mean free path: converted as reflectances, then σ_a, σ_s computed per channel
//                (chiang2016_rgb_coefficients), as an RGB renderer applies that parameterisation;
//   RGB inputs, image textures and environment images: used as given (converted to linear sRGB if given in another
//                space), never upsampled.
// Inputs the loader leaves spectral (a named metal's n and k) are point-sampled at the nominal lane wavelengths
// (transport/sampling/wavelength_modes.h).
#pragma once

#include <memory>

#include "render/image/rgb_image.h"
#include "render/scene/spectrum_input.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "transport/lights/radiance_image.h"
#include "transport/media/homogeneous_medium.h"
#include "transport/textures/spectral_texture.h"

namespace rimu {

/// A spectral input as rgb transport carries it: lanes 0, 1, 2 hold linear sRGB R, G, B whatever the wavelengths
/// (lane 3 repeats G so that it stays finite; the film ignores it). value() is the original spectrum's, so load-time
/// integrals (light power for the light sampler, photometric scaling) are the same as in spectral mode.
class RgbLaneSpectrum final : public Spectrum {
 public:
  RgbLaneSpectrum(SpectrumPtr original, Rgb linear_srgb);
  double value(double lambda_nm) const override { return original_->value(lambda_nm); }
  SampledSpectrum sample(const SampledWavelengths&) const override { return lanes_; }
  double max_value() const override { return original_->max_value(); }
  std::string describe() const override;
  Rgb linear_srgb() const { return rgb_; }

 private:
  SpectrumPtr original_;
  Rgb rgb_;
  SampledSpectrum lanes_;
};

/// Linear sRGB of a reflectance (D65, perfect diffuser = 1, clipped to [0, 1]). Cost: two 1 nm integrations.
Rgb reflectance_linear_srgb(const Spectrum& reflectance, SpectralLibrary& library);
/// Linear sRGB of a coefficient: as reflectance_linear_srgb, clipped to ≥ 0 only (a constant c gives (c, c, c)).
Rgb coefficient_linear_srgb(const Spectrum& coefficient, SpectralLibrary& library);
/// Linear sRGB of an emission from its film XYZ (negative channels clipped to 0). Cost: one 1 nm integration.
Rgb emission_linear_srgb(const Spectrum& emission, SpectralLibrary& library);
/// Linear RGB of colour space `space` expressed in linear sRGB (through XYZ, no chromatic adaptation).
Rgb to_linear_srgb(const Rgb& rgb, const RgbColourSpace& space);

/// The rgb-transport form of a loaded spectrum for its role (see the file comment). `given_linear_srgb`, if set, is
/// the RGB the user wrote (already in linear sRGB, scale applied): it is used as is instead of converting.
SpectrumPtr rgb_transport_form(const SpectrumPtr& spectrum, SpectrumRole role, SpectralLibrary& library,
                               const Rgb* given_linear_srgb = nullptr);

/// A medium's coefficients in rgb transport (RgbLaneSpectrum; the spectral originals answer value()).
struct RgbMediumCoefficients {
  SpectrumPtr sigma_a, sigma_s;
};
/// Chiang et al. 2016's parameterisation applied per channel (chiang2016_coefficients on each of R, G, B; d in
/// metres). `spectral` gives the originals.
RgbMediumCoefficients chiang2016_rgb_coefficients(const HomogeneousMedium& spectral, Rgb surface_albedo,
                                                  Rgb mean_free_path_m);

/// An environment or emission image in rgb transport: each pixel's linear sRGB in lanes 0-2 (lane 3 repeats G),
/// negative channels clipped to 0, no upsampling. Pixel values are film units as in spectral mode (an RGB of
/// luminance Y renders with film Y), so the light's scale is the user's alone (no cd/m² conversion). Luminance for
/// importance sampling is the pixel's Y, as RgbRadianceImage's.
class RgbLaneRadianceImage final : public RadianceImage {
 public:
  RgbLaneRadianceImage(std::shared_ptr<const RgbImage> image, const RgbColourSpace& space);
  int width() const override { return image_->width(); }
  int height() const override { return image_->height(); }
  SampledSpectrum radiance(int x, int y, const SampledWavelengths& lambda) const override;
  float luminance(int x, int y) const override;

 private:
  std::shared_ptr<const RgbImage> image_;
  const RgbColourSpace& space_;
  Matrix3 to_srgb_;  // the image's space → linear sRGB
};

/// An image reflectance texture in rgb transport: bilinear RGB, scaled and inverted as ImageTexture's texels
/// (scaled_texel), converted to linear sRGB, clipped to [0, 1]; no upsampling (compare render/image/image_texture.h).
class RgbLaneImageTexture final : public SpectralTexture {
 public:
  RgbLaneImageTexture(std::shared_ptr<const RgbImage> image, const RgbColourSpace& space, float scale, bool invert = false);
  SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths& lambda) const override;

 private:
  std::shared_ptr<const RgbImage> image_;
  Matrix3 to_srgb_;  // the image's space → linear sRGB
  float scale_;
  bool invert_;
};

}  // namespace rimu
