#include "render/camera/physical_camera.h"

#include <cmath>

#include "spectral/error.h"
#include "spectral/photometry/light_units.h"
#include "spectral/colorimetry/photometry_constants.h"

namespace rimu {
namespace {

void check(const PhysicalCameraSettings& c) {
  if (!(c.iso > 0.0) || !(c.shutter_s > 0.0) || !(c.f_number > 0.0) || !std::isfinite(c.exposure_compensation_ev))
    throw InputError({}, "a physical camera needs a positive ISO, shutter time and f-number and a finite exposure "
                         "compensation");
}

}  // namespace

double metered_luminance_nt(const PhysicalCameraSettings& c) {
  check(c);
  return kReflectedMeterConstant * c.f_number * c.f_number / (c.shutter_s * c.iso);
}

double exposure_value(const PhysicalCameraSettings& c) {
  check(c);
  return std::log2(c.f_number * c.f_number / c.shutter_s);
}

double imaging_ratio_per_nit(const PhysicalCameraSettings& c) {
  return kMeterMidGrey * std::exp2(c.exposure_compensation_ev) / metered_luminance_nt(c);
}

double film_exposure_scale(const PhysicalCameraSettings& c, const SpectralResponse& response) {
  const double nits_per_y = response.luminance_nits_per_unit_y();
  // Camera films have no photometric unit; their G channel is normalised like Y (spectral_response.h), so the
  // same factor exposes them as an XYZ film of the same scene would be exposed.
  const double per_unit = nits_per_y > 0.0 ? nits_per_y : kMaxLuminousEfficacy_lm_W * response.normalisation_nm();
  const double scale = imaging_ratio_per_nit(c) * per_unit;
  // Settings far outside a camera's (ISO 1e-300 with f/1e-300…) can underflow N²/(tS) to 0/0 or overflow it: an
  // image of NaN, Inf or zeros is never what was meant.
  if (!std::isfinite(scale) || !(scale > 0.0))
    throw InputError({}, "these physical camera settings (ISO, shutter time, f-number, compensation) give an "
                         "exposure scale of " + std::to_string(scale) + ", outside what an image can hold");
  return scale;
}

std::array<double, 3> film_channels(const Spectrum& spectrum, const SpectralResponse& response) {
  std::array<double, 3> sum{};
  for (int nm = 360; nm <= 830; ++nm) {
    const double w = (nm == 360 || nm == 830) ? 0.5 : 1.0;
    const double s = spectrum.value(nm);
    for (int c = 0; c < 3; ++c) sum[size_t(c)] += w * s * response.value(c, nm);
  }
  return sum;
}

Matrix3 white_balance_matrix(const Spectrum& illuminant, const SpectralResponse& response, SpectralLibrary& library,
                             CatMethod method) {
  const std::array<double, 3> w = film_channels(illuminant, response);
  if (!(w[0] > 0.0 && w[1] > 0.0 && w[2] > 0.0))
    throw InputError({}, "cannot white-balance to '" + illuminant.describe() + "': the film sees no light from it in "
                         "some channel");
  if (response.kind() == ResponseKind::camera_rgb) {
    return Matrix3::diagonal(w[1] / w[0], 1.0, w[1] / w[2]);
  }
  const std::array<double, 3> d65 = film_channels(*library.illuminant("D65"), response);
  return chromatic_adaptation_matrix(Xyz{w[0] / w[1], 1.0, w[2] / w[1]}, Xyz{d65[0] / d65[1], 1.0, d65[2] / d65[1]},
                                     method);
}

}  // namespace rimu
