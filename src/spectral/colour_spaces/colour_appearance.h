// CIECAM02 (CIE 159:2004) and CAM16 (Li et al. 2017) forward and inverse, and their uniform colour spaces
// CAM02-UCS and CAM16-UCS (Luo, Cui & Li 2006; Li et al. 2017). The two models share every step but the
// cone spaces: CIECAM02 adapts in CAT02 and compresses in Hunt-Pointer-Estevez, CAM16 does both in M_16.
// (TM-30's own CAM02-UCS, fixed to D = 1, is cam02_ucs.h; tests check the two agree.)
#pragma once

#include <array>
#include <optional>
#include <string>

#include "spectral/colorimetry/cam02_ucs.h"
#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colour_spaces/matrix3.h"
#include "spectral/error.h"

namespace rimu {

enum class AppearanceModel { ciecam02, cam16 };

/// The surround's F, c and N_c (CIE 159:2004 Table 1; the same for CAM16).
struct Surround {
  double f = 1.0, c = 0.69, n_c = 1.0;
  static Surround average() { return {1.0, 0.69, 1.0}; }
  static Surround dim() { return {0.9, 0.59, 0.9}; }
  static Surround dark() { return {0.8, 0.525, 0.8}; }
};
/// "average", "dim" or "dark"; InputError at `where` otherwise.
Surround surround_option(const std::string& name, const SourceLocation& where);

struct ViewingConditions {
  Xyz white{95.047, 100.0, 108.883};      ///< the adopted white, on the scale of the colours (Y_w = 100 usually)
  double adapting_luminance_cd_m2 = 64.0 / 3.141592653589793 * 0.2;  ///< L_A (sRGB's 64 lx ambient, 20 % grey)
  double background_y = 20.0;             ///< Y_b, on the white's scale
  Surround surround = Surround::average();
  /// D: computed from F and L_A (CIE 159 eq. 7.3, clipped to [0, 1]) when empty; 1 when the illuminant is
  /// discounted.
  std::optional<double> degree_of_adaptation;
};

/// The appearance correlates: lightness J, chroma C, hue angle h (degrees, [0, 360)), colourfulness M,
/// saturation s, brightness Q and hue quadrature H (0-400).
struct Appearance {
  double j = 0, c = 0, h_deg = 0, m = 0, s = 0, q = 0, hue_quadrature = 0;
};

/// One model fixed to one set of viewing conditions: build once, convert many colours.
class ColourAppearanceModel {
 public:
  ColourAppearanceModel(AppearanceModel model, const ViewingConditions& conditions);

  Appearance forward(const Xyz& xyz) const;
  /// XYZ from lightness J, colourfulness M and hue angle h (degrees): the inverse of forward().
  Xyz inverse(double j, double m, double h_deg) const;

  /// The uniform colour space's J', a', b' (c1 = 0.007, c2 = 0.0228 for both models).
  static Jab ucs_of(const Appearance& appearance);
  /// J, M, h from J', a', b': the inverse of ucs_of.
  static Appearance appearance_of_ucs(const Jab& jab);

  double luminance_adaptation_factor() const { return f_l_; }
  double degree_of_adaptation() const { return d_; }
  AppearanceModel model() const { return model_; }

 private:
  // Cone signals after adaptation and compression (R'a, G'a, B'a) of XYZ.
  std::array<double, 3> compressed_responses(const Xyz& xyz) const;

  AppearanceModel model_;
  ViewingConditions v_;
  Matrix3 to_adaptation_, from_adaptation_;  // XYZ <-> the adaptation space
  Matrix3 adapted_to_compression_, compression_to_adapted_;  // adaptation space <-> compression space
  double d_rgb_[3]{};
  double d_ = 1, f_l_ = 1, n_ = 0.2, n_bb_ = 1, z_ = 1, achromatic_white_ = 1;
};

}  // namespace rimu
