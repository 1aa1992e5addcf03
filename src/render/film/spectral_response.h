// The three response curves a film integrates radiance against: CIE XYZ (2° or 10°) or a camera's R, G, B.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/colorimetry/observer.h"
#include "spectral/colour_spaces/matrix3.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

/// What the three film channels mean.
enum class ResponseKind {
  cie_xyz,     ///< CIE XYZ tristimulus values (channels X, Y, Z)
  camera_rgb,  ///< a measured sensor's raw R, G, B (no colour correction)
};

/// Three response curves c_k(λ), k = 0, 1, 2, already normalised, evaluated per lane by the film.
///
/// Normalisation (the film value of a pixel is ∫ L(λ) c_k(λ) dλ):
/// - CIE XYZ: c = (x̄, ȳ, z̄) / ∫ȳ dλ, so XYZ = ∫ L x̄ dλ / ∫ ȳ dλ. An equal-energy spectral radiance of
///   1 W/(m²·sr·nm) gives Y = 1 (and X = ∫x̄/∫ȳ, Z = ∫z̄/∫ȳ). The absolute luminance in cd/m² (nits) is
///   Y · luminance_nits_per_unit_y() = Y · 683 lm/W · ∫ȳ dλ (≈ 72 983 nits for the 1931 observer).
/// - Camera RGB: c = (r̄, ḡ, b̄) / ∫ḡ dλ, so the equal-energy radiance of 1 W/(m²·sr·nm) gives G = 1.
///   Sensors are measured over a limited range (e.g. 380-720 nm); the response is zero outside it.
///
/// The integrals are exact integrals over 360-830 nm of the piecewise-linear curves the per-sample path evaluates
/// (TabulatedSpectrum::sample(), zero outside a camera's measured range), so the film's estimate of a constant
/// radiance is unbiased to float rounding.
class SpectralResponse {
 public:
  /// CIE XYZ with the given standard observer.
  static SpectralResponse cie_xyz(SpectralLibrary& library, StandardObserver observer = StandardObserver::cie1931_2deg);
  /// A camera from data/spectra/cameras by name: the file stem ("pbrt_physlight_nikon_d850_10nm") or the stem
  /// without its source prefix and step suffix ("nikon_d850"). Throws InputError listing the known names when the
  /// name is unknown or the short name is ambiguous (e.g. "nikon_d5100" is measured by both NPL and rawtoaces).
  static SpectralResponse camera_rgb(SpectralLibrary& library, std::string_view name);
  /// The film of the rgb transport baseline (WavelengthMode::rgb): lanes 0-2 carry linear sRGB, and the film turns
  /// them into CIE 1931 XYZ with the sRGB matrix (IEC 61966-2-1) instead of response curves. kind() is cie_xyz.
  static SpectralResponse rgb_transport(SpectralLibrary& library);
  /// A camera film whose channels are XYZ: the curves M·(r̄, ḡ, b̄) of `camera` (kind cie_xyz, in the XYZ film's
  /// units), with M from fit_camera_to_xyz_under (render/film/camera_colour_matrix.h), which holds the white
  /// balance: pbrt-v4's sensor pipeline (a film "response" of "camera-xyz:<name>"). The matrix acts on each sample,
  /// as pbrt's does on its sensor RGB, and being linear it commutes with the film's sums. Curves may dip below zero
  /// (the fit's), so a channel of a sample may be negative; the radiance never is.
  static SpectralResponse colour_corrected(const SpectralResponse& camera, const Matrix3& camera_to_xyz,
                                           SpectralLibrary& library, const std::string& white_description);
  /// Whether the white balance is part of the curves (colour_corrected): the film's output then applies none.
  bool white_balance_in_curves() const { return white_balance_in_curves_; }
  /// A film response from the CLI's spelling: "xyz" (1931 2°), "xyz10" (1964 10°), "camera:<name>" (raw R, G, B) or
  /// "camera-xyz:<name>" (colour_corrected, white balanced to `white`, D65 without one; described as
  /// `white_description`).
  static SpectralResponse from_spec(SpectralLibrary& library, std::string_view spec, const Spectrum* white = nullptr,
                                    const std::string& white_description = "D65");
  /// Every camera file stem in data/spectra/cameras, sorted.
  static std::vector<std::string> camera_file_stems(const SpectralLibrary& library);
  /// The short name of a camera file stem: source prefix and "_<step>nm" suffix removed.
  static std::string camera_short_name(std::string_view file_stem);

  /// The three normalised responses at the four wavelengths (per-sample path; no allocation).
  /// For an rgb-transport film the lanes are not wavelengths: cₖ(lane j) = M_sRGB→XYZ[k][j] (lane 3 is 0).
  Response4 evaluate(const SampledWavelengths& lambda) const {
    return lanes_are_rgb_ ? rgb_lane_matrix_ : curves_.sample(lambda);
  }
  /// True for rgb_transport(): the lanes carry linear sRGB (transport/sampling/wavelength_modes.h).
  bool lanes_are_rgb() const { return lanes_are_rgb_; }
  /// One normalised response at one wavelength (setup and tests).
  double value(int channel, double lambda_nm) const;

  ResponseKind kind() const { return kind_; }
  /// "X","Y","Z" or "R","G","B".
  const std::array<std::string, 3>& channel_names() const { return channel_names_; }
  /// Human-readable description for metadata, e.g. "CIE 1931 2°" or "camera nikon_d850 (pbrt_physlight_nikon_d850_10nm)".
  const std::string& description() const { return description_; }
  /// The camera's file stem (empty for XYZ).
  const std::string& camera_name() const { return camera_name_; }
  /// ∫ of the un-normalised middle curve (ȳ or ḡ) over 360-830 nm, in nm × curve units: the divisor applied.
  double normalisation_nm() const { return normalisation_nm_; }
  /// For XYZ films: cd/m² per unit of film Y, 683 lm/W · ∫ȳ dλ. Zero for camera films (no photometric meaning).
  double luminance_nits_per_unit_y() const;

 private:
  SpectralResponse(ResponseKind kind, Observer curves, double normalisation_nm, std::string description,
                   std::string camera_name);

  ResponseKind kind_;
  Observer curves_;  // normalised x̄,ȳ,z̄ or r̄,ḡ,b̄
  double normalisation_nm_;
  std::string description_;
  std::string camera_name_;
  bool white_balance_in_curves_ = false;
  std::array<std::string, 3> channel_names_;
  bool lanes_are_rgb_ = false;
  Response4 rgb_lane_matrix_{};
};

/// The exact integral over 360-830 nm, in nm × curve units, of the piecewise-linear function a TabulatedSpectrum is.
double integral_as_sampled_nm(const TabulatedSpectrum& curve);

}  // namespace rimu
