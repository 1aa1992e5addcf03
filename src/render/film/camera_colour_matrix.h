// A camera film's colour-correction matrix: the 3×3 that best turns its raw R, G, B into CIE 1931 XYZ.
//
// A sensor's curves are not a linear combination of the colour-matching functions (the Luther condition fails), so
// no matrix is exact; the usual characterisation (e.g. ISO 17321-1's, or Hong, Luo & Rhodes, "A study of digital
// camera colorimetric characterisation based on polynomial modelling", Color Res. Appl. 26(1), 2001) fits one over
// a training set of surface colours under one illuminant. Rimu's training set is the 24 patches of the ColorChecker
// Classic (data/spectra/reflectances, BabelColor average) under CIE D65, the white the display assumes:
//   c_i = ∫ D65(λ) ρ_i(λ) r̄ḡb̄(λ) dλ,  x_i = ∫ D65(λ) ρ_i(λ) x̄ȳz̄(λ) dλ   (both films' own normalisation),
//   M = argmin Σ_i ‖M c_i − x_i‖² = (Σ x_i c_iᵀ)(Σ c_i c_iᵀ)⁻¹       (ordinary least squares in XYZ),
// integrated at 1 nm over 360-830 nm with the trapezoid rule. The residual is reported as CIEDE2000 between M c_i
// and x_i, in CIELAB relative to the perfect reflector under D65.
#pragma once

#include <string>

#include "render/film/spectral_response.h"
#include "spectral/colour_spaces/matrix3.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

struct CameraColourFit {
  /// Film R, G, B (raw, before white balance) → XYZ in the XYZ film's units (Y = 1 for an equal-energy radiance of
  /// 1 W/(m²·sr·nm)), so a camera film shown through it is as bright as an XYZ film of the same scene.
  Matrix3 camera_to_xyz;
  double mean_delta_e2000 = 0;  ///< over the training patches
  double max_delta_e2000 = 0;
  std::string worst_patch;      ///< the patch with max_delta_e2000
  int patch_count = 0;
  /// The camera's raw R, G, B for D65 (the white of the fit), for display through a white balance.
  std::array<double, 3> d65_white_rgb{};
};

/// Fits camera_to_xyz for `camera` (any response; for an XYZ film the answer is the identity with zero residual).
/// Cost: 24 patches × 471 wavelengths, well under a millisecond. Throws InputError if the training colours do not
/// span three dimensions for this response (a degenerate sensor).
CameraColourFit fit_camera_to_xyz(const SpectralResponse& camera, SpectralLibrary& library);

/// pbrt-v4's sensor pipeline (its PixelSensor): the matrix that turns the camera's raw R, G, B of the ColorChecker
/// patches lit by `white` (the white-balance illuminant) into the XYZ of the same patches lit by D65, scaled by
/// Y(white)/Y(D65) so that a white lit by `white` keeps its luminance and is rendered with D65's chromaticity:
/// white balance by the fit (a chromatic adaptation learnt on the patches) rather than by per-channel gains. The
/// same least squares as fit_camera_to_xyz, whose matrix this is when `white` is D65. Throws as fit_camera_to_xyz.
Matrix3 fit_camera_to_xyz_under(const SpectralResponse& camera, const Spectrum& white, SpectralLibrary& library);

/// The matrix the display applies to a camera film's written R, G, B (which include the white balance M_wb of
/// render/film/film_output_transform.h, possibly the identity). Without white balance: camera_to_xyz. With one, the
/// balanced neutral R = G = B is taken as the camera's D65 white: camera_to_xyz · diag(d65_R/d65_G, 1, d65_B/d65_G),
/// so whatever the camera was balanced to is shown as D65 (the display's white), as a camera's own JPEG does.
Matrix3 display_camera_to_xyz(const CameraColourFit& fit, bool white_balanced);

}  // namespace rimu
