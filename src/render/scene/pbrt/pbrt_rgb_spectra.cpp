// pbrt-v4's RGB spectra for the file's constant RGB parameters (docs/pbrt-import.md, "RGB parameters"): pbrt
// turns an RGB into a sigmoid polynomial (Jakob & Hanika 2019) — RGBAlbedoSpectrum for reflectances,
// RGBUnboundedSpectrum (2·max times the albedo fit of rgb/(2·max)) for optical constants and coefficients,
// RGBIlluminantSpectrum (the unbounded fit times the colour space's illuminant) for lights. The importer fits the
// same function space to the same colour (sigmoid_polynomial.h) and writes the spectrum as a 1 nm table, so a
// pbrt scene renders with pbrt's spectra rather than Rimu's smoothest ones wherever light meets two coloured
// surfaces (the spectra's products differ even where their colours agree).
#include <algorithm>

#include "render/scene/pbrt/pbrt_converter.h"
#include "spectral/upsampling/upsampling_whites.h"

namespace rimu {

const SigmoidSpectrum& PbrtConverter::sigmoid_fit(const Rgb& rgb, bool unbounded, const std::string& colour_space,
                                                  const SourceLocation& where) {
  const auto key = std::make_tuple(colour_space, unbounded, rgb.r, rgb.g, rgb.b);
  if (const auto found = sigmoid_fits_.find(key); found != sigmoid_fits_.end()) return found->second;
  std::unique_ptr<SigmoidFitter>& fitter = sigmoid_fitters_[colour_space];
  if (!fitter) fitter = std::make_unique<SigmoidFitter>(library_, RgbColourSpace::named(colour_space));
  const SigmoidSpectrum fit = unbounded ? fitter->fit_unbounded(rgb, where) : fitter->fit_albedo(rgb, where);
  return sigmoid_fits_.emplace(key, fit).first->second;
}

json PbrtConverter::sigmoid_table(const SigmoidSpectrum& s, const Spectrum* illuminant) {
  json nm = json::array(), values = json::array();
  for (int wavelength_nm = 360; wavelength_nm <= 830; ++wavelength_nm) {
    nm.push_back(wavelength_nm);
    values.push_back(s.value(wavelength_nm) * (illuminant ? illuminant->value(wavelength_nm) : 1.0));
  }
  return json{{"wavelengths_nm", nm}, {"values", values}};
}

json PbrtConverter::rgb_reflectance(const PbrtParam& param) {
  const Rgb rgb{param.numbers.at(0), param.numbers.at(1), param.numbers.at(2)};
  // pbrt's albedo spectrum holds RGB within [0, 1] only; Rimu's upsampler maps brighter colours into its gamut.
  if (rgb_upsampler_ == PbrtRgbUpsampler::rimu || std::max({rgb.r, rgb.g, rgb.b}) > 1)
    return json{{"rgb", param.numbers}, {"space", state_.colour_space}};
  if (rgb.r == rgb.g && rgb.g == rgb.b) return rgb.r;  // a grey is its constant, in both upsamplers
  return sigmoid_table(sigmoid_fit(rgb, false, state_.colour_space, param.where));
}

std::optional<json> PbrtConverter::rgb_illuminant_shape(const PbrtParam& param) {
  if (rgb_upsampler_ == PbrtRgbUpsampler::rimu) return std::nullopt;
  const Rgb rgb{param.numbers.at(0), param.numbers.at(1), param.numbers.at(2)};
  const RgbColourSpace& space = RgbColourSpace::named(state_.colour_space);
  const TabulatedSpectrum illuminant = upsampling_illuminant(library_, upsampling_white_for(space.white()));
  return sigmoid_table(sigmoid_fit(rgb, true, state_.colour_space, param.where), &illuminant);
}

}  // namespace rimu
