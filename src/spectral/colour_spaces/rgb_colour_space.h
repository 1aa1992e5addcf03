// RGB colour spaces defined by their primaries and white point; the matrices are derived, never pasted.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colour_spaces/matrix3.h"

namespace rimu {

/// Linear RGB values (no transfer function applied).
struct Rgb {
  double r = 0, g = 0, b = 0;
};

/// A linear RGB colour space: three primaries and a white point, all as CIE 1931 xy.
///
/// rgb_to_xyz is derived the standard way (SMPTE RP 177-1993): the columns are the primaries' XYZ (at Y = 1)
/// scaled so that RGB (1,1,1) maps to the white point with Y = 1. Encoding transfer functions (the sRGB curve)
/// are separate functions, because every renderer-internal colour is linear.
class RgbColourSpace {
 public:
  RgbColourSpace(std::string name, Chromaticity red, Chromaticity green, Chromaticity blue, Chromaticity white);

  /// A built-in space by name: "srgb-linear" (= Rec.709), "rec2020", "display-p3" (linear), "aces2065-1",
  /// "acescg", "cie-rgb". Throws InputError listing the names.
  static const RgbColourSpace& named(std::string_view name);
  /// The canonical names of the built-in spaces (aliases such as "rec709" are accepted by named() but not listed).
  static std::vector<std::string> names();

  const std::string& name() const { return name_; }
  Chromaticity red() const { return red_; }
  Chromaticity green() const { return green_; }
  Chromaticity blue() const { return blue_; }
  Chromaticity white() const { return white_; }

  /// Linear RGB → XYZ with Y(white) = 1.
  const Matrix3& rgb_to_xyz() const { return rgb_to_xyz_; }
  const Matrix3& xyz_to_rgb() const { return xyz_to_rgb_; }
  Xyz to_xyz(const Rgb& rgb) const;
  Rgb from_xyz(const Xyz& xyz) const;

 private:
  std::string name_;
  Chromaticity red_, green_, blue_, white_;
  Matrix3 rgb_to_xyz_, xyz_to_rgb_;
};

/// The sRGB (IEC 61966-2-1) encoding transfer function and its inverse, per channel.
double srgb_encode(double linear);
double srgb_decode(double encoded);

}  // namespace rimu
