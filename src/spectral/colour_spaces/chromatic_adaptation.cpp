#include "spectral/colour_spaces/chromatic_adaptation.h"

#include <cassert>

namespace rimu {

CatMethod cat_method_option(const std::string& name, const SourceLocation& where) {
  if (name == "bradford") return CatMethod::bradford;
  if (name == "cat02") return CatMethod::cat02;
  if (name == "cat16") return CatMethod::cat16;
  if (name == "von-kries") return CatMethod::von_kries;
  if (name == "xyz-scaling") return CatMethod::xyz_scaling;
  throw InputError(where, "expected bradford, cat02, cat16, von-kries or xyz-scaling, got '" + name + "'");
}

Matrix3 cone_response_matrix(CatMethod method) {
  switch (method) {
    case CatMethod::bradford:
      // Lam (1985), linearised Bradford matrix as used by ICC.1:2010 Annex E and CIECAM97s.
      return {{{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}}};
    case CatMethod::cat02:
      // CIE 159:2004 (CIECAM02) eq. 7, M_CAT02.
      return {{{{0.7328, 0.4296, -0.1624}, {-0.7036, 1.6975, 0.0061}, {0.0030, 0.0136, 0.9834}}}};
    case CatMethod::cat16:
      // Li, Li, Wang, Xu, Luo, Cui, Melgosa, Brill & Pointer (2017), "Comprehensive color solutions: CAM16, CAT16,
      // and CAM16-UCS", Color Res. Appl. 42(6):703-718, eq. 4, M_16.
      return {{{{0.401288, 0.650173, -0.051461}, {-0.250268, 1.204414, 0.045854}, {-0.002079, 0.048952, 0.953127}}}};
    case CatMethod::von_kries:
      // Hunt-Pointer-Estevez cone fundamentals (Hunt & Pointer 1985), in the form normalised to D65 that
      // Lindbloom's "Chromatic Adaptation" page lists for von Kries: it sends XYZ(D65) to LMS within 3e-4 of
      // (1, 1, 1). Any normalisation gives the same CAT, since diag scalings commute out of M⁻¹·D·M.
      return {{{{0.40024, 0.70760, -0.08081}, {-0.22630, 1.16532, 0.04570}, {0.0, 0.0, 0.91822}}}};
    case CatMethod::xyz_scaling:
      return Matrix3::identity();
  }
  assert(false && "unknown CatMethod");
  return Matrix3::identity();
}

Matrix3 chromatic_adaptation_matrix(Xyz source_white, Xyz destination_white, CatMethod method) {
  // The von Kries hypothesis: adaptation multiplies each cone signal by a gain, chosen so the adapted source
  // white produces the destination white's cone signals. In XYZ that is the similarity transform below.
  const Matrix3 to_cone = cone_response_matrix(method);
  const Xyz source_cone = to_cone.apply(source_white);
  const Xyz destination_cone = to_cone.apply(destination_white);
  assert(source_cone.x != 0.0 && source_cone.y != 0.0 && source_cone.z != 0.0 && "source white has a zero cone signal");
  const Matrix3 gain = Matrix3::diagonal(destination_cone.x / source_cone.x, destination_cone.y / source_cone.y,
                                         destination_cone.z / source_cone.z);
  return to_cone.inverse() * gain * to_cone;
}

Xyz white_point_xyz(const RgbColourSpace& space) { return xyz_from_xyY(space.white(), 1.0); }

Matrix3 rgb_conversion_matrix(const RgbColourSpace& source, const RgbColourSpace& destination, CatMethod method) {
  const Matrix3 adapt = chromatic_adaptation_matrix(white_point_xyz(source), white_point_xyz(destination), method);
  return destination.xyz_to_rgb() * adapt * source.rgb_to_xyz();
}

}  // namespace rimu
