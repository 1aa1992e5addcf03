#include "spectral/colorimetry/colour_value_check.h"

#include <cmath>
#include <sstream>

namespace rimu {
namespace {

std::string triple(double a, double b, double c) {
  std::ostringstream out;
  out << "(" << a << ", " << b << ", " << c << ")";
  return out.str();
}

}  // namespace

void check_colour_component(double v, const SourceLocation& where) {
  if (!(std::abs(v) <= kMaxColourComponent)) {
    std::ostringstream out;
    out << "expected a finite number in [-1e30, 1e30]; got " << v;
    throw InputError(where, out.str());
  }
}

void check_colour_components(double a, double b, double c, const SourceLocation& where) {
  for (double v : {a, b, c})
    if (!(std::abs(v) <= kMaxColourComponent))
      throw InputError(where, "expected three finite components in [-1e30, 1e30]; got " + triple(a, b, c));
}

void check_white_xyz(const Xyz& white, const SourceLocation& where) {
  for (double v : {white.x, white.y, white.z})
    if (!(v >= 1.0 / kMaxColourComponent && v <= kMaxColourComponent))
      throw InputError(where, "a reference white needs X, Y and Z in [1e-30, 1e30]; got " +
                                  triple(white.x, white.y, white.z));
}

void check_has_chromaticity(const Xyz& xyz, const SourceLocation& where) {
  check_colour_components(xyz.x, xyz.y, xyz.z, where);
  if (!(xyz.x + xyz.y + xyz.z > 0.0))
    throw InputError(where, "X + Y + Z of " + triple(xyz.x, xyz.y, xyz.z) +
                                " is not positive, so it has no chromaticity (black has none)");
}

void check_has_ucs_chromaticity(const Xyz& xyz, const SourceLocation& where) {
  check_has_chromaticity(xyz, where);
  if (!(xyz.x + 15.0 * xyz.y + 3.0 * xyz.z > 0.0))
    throw InputError(where, "X + 15Y + 3Z of " + triple(xyz.x, xyz.y, xyz.z) +
                                " is not positive, so it has no (u, v) or (u', v') chromaticity");
}

}  // namespace rimu
