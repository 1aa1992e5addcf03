// Tristimulus values and the chromaticity coordinates derived from them.
#pragma once

namespace rimu {

/// CIE XYZ tristimulus values. The scale depends on where they came from: relative colorimetry uses
/// Y = 100 (or 1) for the perfect diffuser; absolute emission uses Y in cd/m² (see colorimetry.h).
struct Xyz {
  double x = 0, y = 0, z = 0;
};

/// CIE 1931 (x, y) chromaticity.
struct Chromaticity {
  double x = 0, y = 0;
};

/// CIE 1960 UCS (u, v) and CIE 1976 UCS (u', v') coordinates.
struct Uv1960 {
  double u = 0, v = 0;
};
struct Uv1976 {
  double u = 0, v = 0;
};

/// xy of XYZ; (0,0) for black (X+Y+Z = 0), where chromaticity is undefined.
Chromaticity chromaticity_of(const Xyz& xyz);
/// XYZ from chromaticity and luminance Y; (0,0,0) if y = 0.
Xyz xyz_from_xyY(Chromaticity xy, double luminance_y);
Uv1960 uv1960_of(const Xyz& xyz);
Uv1976 uv1976_of(const Xyz& xyz);
Uv1960 uv1960_of(Chromaticity xy);
Uv1976 uv1976_of(Chromaticity xy);
Chromaticity chromaticity_of(Uv1960 uv);

}  // namespace rimu
