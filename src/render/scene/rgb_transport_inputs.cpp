#include "render/scene/rgb_transport_inputs.h"

#include "render/image/image_texture.h"

#include <algorithm>
#include <array>
#include <sstream>

#include "render/film/spectral_response.h"
#include "spectral/colorimetry/colorimetry.h"

namespace rimu {
namespace {

const RgbColourSpace& srgb() { return RgbColourSpace::named("srgb-linear"); }

Rgb clipped(Rgb c, double high) {
  return {std::clamp(c.r, 0.0, high), std::clamp(c.g, 0.0, high), std::clamp(c.b, 0.0, high)};
}

// The lanes rgb transport carries for a linear sRGB: R, G, B, and G again in the dead lane 3 (it stays finite).
SampledSpectrum srgb_lanes(Rgb c) { return SampledSpectrum(float(c.r), float(c.g), float(c.b), float(c.g)); }

// An image value in its own space, as linear sRGB clipped to [0, high].
Rgb image_value_in_srgb(const Matrix3& to_srgb, Rgb texel, double high) {
  const std::array<double, 3> c = to_srgb.apply(std::array<double, 3>{texel.r, texel.g, texel.b});
  return clipped({c[0], c[1], c[2]}, high);
}

// Linear sRGB of a spectrum read as a reflectance under D65, relative to the perfect diffuser (before clipping).
Rgb relative_linear_srgb(const Spectrum& spectrum, SpectralLibrary& library) {
  const Observer& observer = library.observer(StandardObserver::cie1931_2deg);
  const SpectrumPtr d65 = library.illuminant("D65");
  // Both XYZ have the perfect diffuser at Y = 100 (CIE 15:2004 eq. 7.2); the per-channel division removes the
  // small mismatch between the tabulated D65 white and the sRGB matrix's (x, y) = (0.3127, 0.3290).
  const Rgb sample = srgb().from_xyz(reflectance_xyz(spectrum, *d65, observer));
  const Rgb white = srgb().from_xyz(illuminant_xyz(*d65, observer));
  return {sample.r / white.r, sample.g / white.g, sample.b / white.b};
}

}  // namespace

RgbLaneSpectrum::RgbLaneSpectrum(SpectrumPtr original, Rgb linear_srgb)
    : original_(std::move(original)),
      rgb_(linear_srgb),
      lanes_(srgb_lanes(linear_srgb)) {}

std::string RgbLaneSpectrum::describe() const {
  std::ostringstream out;
  out << "linear sRGB (" << rgb_.r << ", " << rgb_.g << ", " << rgb_.b << ") for rgb transport of "
      << original_->describe();
  return out.str();
}

Rgb reflectance_linear_srgb(const Spectrum& reflectance, SpectralLibrary& library) {
  return clipped(relative_linear_srgb(reflectance, library), 1.0);
}

Rgb coefficient_linear_srgb(const Spectrum& coefficient, SpectralLibrary& library) {
  return clipped(relative_linear_srgb(coefficient, library), 1e30);
}

RgbMediumCoefficients chiang2016_rgb_coefficients(const HomogeneousMedium& spectral, Rgb surface_albedo,
                                                  Rgb mean_free_path_m) {
  const Chiang2016Coefficients r = chiang2016_coefficients(surface_albedo.r, mean_free_path_m.r),
                               g = chiang2016_coefficients(surface_albedo.g, mean_free_path_m.g),
                               b = chiang2016_coefficients(surface_albedo.b, mean_free_path_m.b);
  const Rgb sigma_a{r.sigma_a_per_m, g.sigma_a_per_m, b.sigma_a_per_m};
  const Rgb sigma_s{r.sigma_s_per_m, g.sigma_s_per_m, b.sigma_s_per_m};
  return {std::make_shared<RgbLaneSpectrum>(spectral.sigma_a(), sigma_a),
          std::make_shared<RgbLaneSpectrum>(spectral.sigma_s(), sigma_s)};
}

Rgb emission_linear_srgb(const Spectrum& emission, SpectralLibrary& library) {
  const SpectralResponse film = SpectralResponse::cie_xyz(library);
  Xyz xyz;
  xyz.x = integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) { return emission.value(l) * film.value(0, l); });
  xyz.y = integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) { return emission.value(l) * film.value(1, l); });
  xyz.z = integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) { return emission.value(l) * film.value(2, l); });
  return clipped(srgb().from_xyz(xyz), 1e30);
}

Rgb to_linear_srgb(const Rgb& rgb, const RgbColourSpace& space) {
  if (space.name() == srgb().name()) return rgb;
  return srgb().from_xyz(space.to_xyz(rgb));
}

SpectrumPtr rgb_transport_form(const SpectrumPtr& spectrum, SpectrumRole role, SpectralLibrary& library,
                               const Rgb* given_linear_srgb) {
  if (given_linear_srgb) {
    const Rgb given = role == SpectrumRole::reflectance ? clipped(*given_linear_srgb, 1.0) : clipped(*given_linear_srgb, 1e30);
    return std::make_shared<RgbLaneSpectrum>(spectrum, given);
  }
  switch (role) {
    case SpectrumRole::reflectance:
      return std::make_shared<RgbLaneSpectrum>(spectrum, reflectance_linear_srgb(*spectrum, library));
    case SpectrumRole::emission:
      return std::make_shared<RgbLaneSpectrum>(spectrum, emission_linear_srgb(*spectrum, library));
    case SpectrumRole::ior:
      return std::make_shared<ConstantSpectrum>(spectrum->value(550.0));
    case SpectrumRole::coefficient:
      return std::make_shared<RgbLaneSpectrum>(spectrum, coefficient_linear_srgb(*spectrum, library));
  }
  return spectrum;
}

RgbLaneRadianceImage::RgbLaneRadianceImage(std::shared_ptr<const RgbImage> image, const RgbColourSpace& space)
    : image_(std::move(image)), space_(space), to_srgb_(srgb().xyz_to_rgb() * space.rgb_to_xyz()) {}

SampledSpectrum RgbLaneRadianceImage::radiance(int x, int y, const SampledWavelengths&) const {
  return srgb_lanes(image_value_in_srgb(to_srgb_, image_->pixel(x, y), 1e30));
}

float RgbLaneRadianceImage::luminance(int x, int y) const {
  const double y_value = space_.to_xyz(image_->pixel(x, y)).y;
  return y_value > 0.0 ? float(y_value) : 0.0f;
}

RgbLaneImageTexture::RgbLaneImageTexture(std::shared_ptr<const RgbImage> image, const RgbColourSpace& space,
                                         float scale, bool invert)
    : image_(std::move(image)), to_srgb_(srgb().xyz_to_rgb() * space.rgb_to_xyz()), scale_(scale), invert_(invert) {}

SampledSpectrum RgbLaneImageTexture::evaluate(Vec2 uv, const SampledWavelengths&) const {
  return srgb_lanes(image_value_in_srgb(to_srgb_, scaled_texel(image_->bilinear(uv), scale_, invert_), 1.0));
}

}  // namespace rimu
