// Von Kries-type chromatic adaptation transforms (CATs): scale cone-like responses by the ratio of two whites.
#pragma once

#include <string>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/error.h"
#include "spectral/colour_spaces/matrix3.h"
#include "spectral/colour_spaces/rgb_colour_space.h"

namespace rimu {

/// The "cone" space in which a von Kries-type transform scales the three channels independently.
enum class CatMethod {
  bradford,     ///< Lam (1985) / Luo & Rhodes, the linear part of the Bradford transform (ICC, Photoshop)
  cat02,        ///< CIE 159:2004 CIECAM02, M_CAT02
  cat16,        ///< Li et al. (2017) CAM16, M_16 (CAT16's one-step form: both whites' cone signals in one space)
  von_kries,    ///< Hunt-Pointer-Estevez cone fundamentals (D65-normalised)
  xyz_scaling,  ///< the identity: scale X, Y, Z themselves (the crudest CAT, for comparison)
};

/// A method by name: bradford, cat02, cat16, von-kries or xyz-scaling. Throws InputError at `where` for any other.
CatMethod cat_method_option(const std::string& name, const SourceLocation& where);

/// The XYZ→cone matrix M_A of a method (rows give L, M, S or the method's sharpened equivalents).
Matrix3 cone_response_matrix(CatMethod method);

/// XYZ→XYZ matrix that maps colours seen under `source_white` to corresponding colours under
/// `destination_white`: M_A⁻¹ · diag(cone(dst) / cone(src)) · M_A. Maps source_white exactly onto
/// destination_white (up to rounding). The whites must share a scale (both Y = 1 or both Y = 100).
Matrix3 chromatic_adaptation_matrix(Xyz source_white, Xyz destination_white, CatMethod method);

/// The white point of an RGB space as XYZ with Y = 1 (what RGB (1,1,1) maps to).
Xyz white_point_xyz(const RgbColourSpace& space);

/// Linear RGB in `source` → linear RGB in `destination`, adapting between their whites with `method`:
/// destination.xyz_to_rgb · CAT(source white → destination white) · source.rgb_to_xyz.
Matrix3 rgb_conversion_matrix(const RgbColourSpace& source, const RgbColourSpace& destination,
                              CatMethod method = CatMethod::bradford);

}  // namespace rimu
