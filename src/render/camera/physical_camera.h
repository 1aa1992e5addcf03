// A camera that exposes like a real one: ISO, shutter time, f-number and exposure compensation give the imaging
// ratio between scene luminance and film value, and white balance adapts the film to a chosen illuminant.
//
// Exposure (the PhysLight approach: Langlands & Fascione, "PhysLight: An end-to-end pipeline for scene-referred
// lighting", DigiPro 2020; adopted by pbrt-v4). A lens of f-number N open for t seconds puts the exposure
// H = q L t / N² (lx·s) on the sensor, q ≈ π/4 for an ideal lens on axis. Rather than model a sensor's gain, Rimu
// pins the overall ratio to the reflected-light meter equation of ISO 2720, N²/t = L S / K with K = 12.5: a surface
// of the luminance the meter calls correct, L_m = K N² / (t S), lands at mid-grey 0.18. So the film value is
//   v = 0.18 · L / L_m · 2^EC = 0.18 · t S 2^EC / (K N²) · L        (L in nt, EC = exposure compensation in EV).
// (The same from H and ISO 12232's standard output sensitivity, where H = 10/S lx·s gives 0.18, is
// 0.18·(π/4)·t S L / (10 N²): 2 % less, the difference between q = π/4 and the q = 0.65·(12.5/10)… that ISO 2720
// folds into K. Rimu uses the meter equation so that metered settings land exactly on 0.18.)
//
// White balance: a von Kries-type transform (chromatic_adaptation.h) in the film's own space. For an XYZ film, the
// chosen illuminant's white (Y = 1) is mapped to D65's by a CAT (Bradford by default) in cone space, so a white
// surface lit by that illuminant comes out with D65's chromaticity, the white of the sRGB/Rec.709 output. For a
// camera-RGB film the sensor's own channels are scaled (diag(G_w/R_w, 1, G_w/B_w) from its raw response to the
// illuminant), which is what a camera's white-balance multipliers do.
#pragma once

#include "render/film/spectral_response.h"
#include "spectral/colour_spaces/chromatic_adaptation.h"
#include "spectral/colour_spaces/matrix3.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

struct PhysicalCameraSettings {
  double iso = 100.0;
  double shutter_s = 1.0 / 100.0;
  double f_number = 16.0;
  double exposure_compensation_ev = 0.0;
};

/// The mid-grey the meter equation targets (an 18 % card).
inline constexpr double kMeterMidGrey = 0.18;

/// The luminance a reflected-light meter (K = 12.5) calls correctly exposed at these settings: K N² / (t S), nt.
double metered_luminance_nt(const PhysicalCameraSettings& camera);
/// The exposure value of the settings, EV = log2(N²/t) (at the camera's ISO; EV100 = EV − log2(S/100)).
double exposure_value(const PhysicalCameraSettings& camera);
/// Film value per nit of scene luminance: 0.18 · 2^EC / L_m. Throws InputError for a non-positive ISO, shutter
/// time or f-number.
double imaging_ratio_per_nit(const PhysicalCameraSettings& camera);
/// The factor to apply to an XYZ film's values (Y = 1 ↔ luminance_nits_per_unit_y nt) to get the exposed image.
/// Throws InputError if it is not a positive finite number (settings far outside a camera's underflow or overflow).
double film_exposure_scale(const PhysicalCameraSettings& camera, const SpectralResponse& response);

/// The 3×3 matrix to apply to the film's channels that white-balances to `illuminant` (see above); `library` gives
/// the observer for XYZ films' D65 white. Throws InputError if the film sees no light from the illuminant.
Matrix3 white_balance_matrix(const Spectrum& illuminant, const SpectralResponse& response, SpectralLibrary& library,
                             CatMethod method = CatMethod::bradford);

/// A film's three channels for `spectrum` (exact 1 nm trapezoid over 360-830 nm of the response curves), as
/// the film would record a radiance of that spectrum.
std::array<double, 3> film_channels(const Spectrum& spectrum, const SpectralResponse& response);

}  // namespace rimu
