// CIECAM02 (CIE 159:2004) forward model and its uniform colour space CAM02-UCS (Luo, Cui & Li 2006), as the
// CIE 2017 colour fidelity index (CIE 224:2017) and ANSI/IES TM-30-20 use them.
#pragma once

#include "spectral/colorimetry/chromaticity.h"

namespace rimu {

/// The viewing conditions CIECAM02 needs. The defaults are CIE 224:2017's: adapting luminance 100 cd/m²,
/// background Y_b = 20, average surround (F = 1, c = 0.69, N_c = 1), complete adaptation (D = 1).
struct Ciecam02Conditions {
  double adapting_luminance_cd_m2 = 100.0;
  double background_y = 20.0;
  double surround_f = 1.0, surround_c = 0.69, surround_nc = 1.0;
  double degree_of_adaptation = 1.0;
};

/// CAM02-UCS coordinates J', a', b' (Luo et al. 2006, with c1 = 0.007, c2 = 0.0228).
struct Jab {
  double j = 0, a = 0, b = 0;
};

/// A CIECAM02 model fixed to one white and one set of conditions: build once, convert many colours.
class Cam02Ucs {
 public:
  /// `white` on the scale of the colours to convert (e.g. Y_w = 100).
  Cam02Ucs(const Xyz& white, const Ciecam02Conditions& conditions = {});
  /// CAM02-UCS J', a', b' of a colour seen under this white.
  Jab jab(const Xyz& xyz) const;

 private:
  Ciecam02Conditions c_;
  double white_y_;
  double white_rgb_[3];  // CAT02 responses of the white
  double f_l_, n_, n_bb_, z_, achromatic_white_;
};

}  // namespace rimu
