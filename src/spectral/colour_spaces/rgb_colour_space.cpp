#include "spectral/colour_spaces/rgb_colour_space.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "spectral/error.h"

namespace rimu {

namespace {

/// XYZ of a chromaticity at Y = 1: (x/y, 1, (1-x-y)/y). Negative y is allowed (ACES AP0 blue has y = -0.077);
/// y = 0 is a point at infinity in XYZ and cannot be a primary or a white.
Xyz xyz_at_unit_luminance(Chromaticity c) { return {c.x / c.y, 1.0, (1.0 - c.x - c.y) / c.y}; }

Matrix3 derive_rgb_to_xyz(const std::string& name, Chromaticity red, Chromaticity green, Chromaticity blue,
                          Chromaticity white) {
  const std::array<std::pair<const char*, Chromaticity>, 4> points = {
      {{"red", red}, {"green", green}, {"blue", blue}, {"white", white}}};
  for (const auto& [which, xy] : points) {
    if (!std::isfinite(xy.x) || !std::isfinite(xy.y) || xy.y == 0.0)
      throw InputError({"", 0, name}, std::string("the ") + which + " chromaticity must be finite with y != 0, got (" +
                                          std::to_string(xy.x) + ", " + std::to_string(xy.y) + ")");
  }
  // SMPTE RP 177-1993: P holds the primaries' XYZ (at Y = 1) as columns. The scale S of each column
  // is chosen so that P·S = W, i.e. RGB (1,1,1) lands on the white with Y = 1; then RGB→XYZ = P·diag(S).
  Matrix3 primaries;
  const Xyz columns[3] = {xyz_at_unit_luminance(red), xyz_at_unit_luminance(green), xyz_at_unit_luminance(blue)};
  for (int c = 0; c < 3; ++c) {
    primaries(0, c) = columns[c].x;
    primaries(1, c) = columns[c].y;
    primaries(2, c) = columns[c].z;
  }
  // The determinant of P is (up to the 1/(y_r y_g y_b) factor) twice the signed area of the primaries' triangle.
  if (std::abs(primaries.determinant()) < 1e-12)
    throw InputError({"", 0, name}, "the three primaries are collinear in the chromaticity diagram");
  const Xyz scale = primaries.inverse().apply(xyz_at_unit_luminance(white));
  // A zero scale means the white lies on the line through two primaries: no RGB triple reaches it with all
  // three channels in play, and RGB→XYZ would be singular.
  if (std::abs(scale.x) < 1e-12 || std::abs(scale.y) < 1e-12 || std::abs(scale.z) < 1e-12)
    throw InputError({"", 0, name}, "the white point lies on the line through two of the primaries");
  return primaries * Matrix3::diagonal(scale.x, scale.y, scale.z);
}

// Chromaticities of the built-in spaces, each from the standard that defines it.
constexpr Chromaticity kD65{0.3127, 0.3290};          // ITU-R BT.709-6 Table 1 item 1.4 (4-decimal D65)
constexpr Chromaticity kAcesWhite{0.32168, 0.33767};  // SMPTE ST 2065-1:2012, the ACES white (~D60)

/// CIE 1931 RGB: primaries at 700, 546.1 and 435.8 nm. Their chromaticities are taken from the CIE 1931
/// RGB→XYZ transformation adopted by the CIE in 1931 (reproduced in Wyszecki & Stiles, Color Science,
/// 2nd ed. 1982, chapter 3):
///   X = 0.49 R + 0.31 G + 0.20 B,  Y = 0.17697 R + 0.81240 G + 0.01063 B,  Z = 0.00 R + 0.01 G + 0.99 B,
/// whose columns are the primaries' XYZ; each row sums to 1, so the white is illuminant E (1/3, 1/3).
/// Defining them this way makes the derived matrix reproduce those 1931 coefficients exactly.
Chromaticity cie1931_primary(double x, double y, double z) { return {x / (x + y + z), y / (x + y + z)}; }

std::vector<RgbColourSpace> make_built_in_spaces() {
  std::vector<RgbColourSpace> spaces;
  // ITU-R BT.709-6 Table 1 items 1.3-1.4; IEC 61966-2-1:1999 uses the same primaries and D65.
  spaces.emplace_back("srgb-linear", Chromaticity{0.640, 0.330}, Chromaticity{0.300, 0.600}, Chromaticity{0.150, 0.060},
                      kD65);
  // ITU-R BT.2020-2 Table 3 items 3.3-3.4.
  spaces.emplace_back("rec2020", Chromaticity{0.708, 0.292}, Chromaticity{0.170, 0.797}, Chromaticity{0.131, 0.046},
                      kD65);
  // SMPTE EG 432-1:2010 (P3) primaries with the D65 white of Apple's Display P3.
  spaces.emplace_back("display-p3", Chromaticity{0.680, 0.320}, Chromaticity{0.265, 0.690}, Chromaticity{0.150, 0.060},
                      kD65);
  // SMPTE ST 2065-1:2012, AP0 primaries.
  spaces.emplace_back("aces2065-1", Chromaticity{0.73470, 0.26530}, Chromaticity{0.00000, 1.00000},
                      Chromaticity{0.00010, -0.07700}, kAcesWhite);
  // Academy S-2014-004 (ACEScg), AP1 primaries.
  spaces.emplace_back("acescg", Chromaticity{0.713, 0.293}, Chromaticity{0.165, 0.830}, Chromaticity{0.128, 0.044},
                      kAcesWhite);
  spaces.emplace_back("cie-rgb", cie1931_primary(0.49, 0.17697, 0.00), cie1931_primary(0.31, 0.81240, 0.01),
                      cie1931_primary(0.20, 0.01063, 0.99), Chromaticity{1.0 / 3.0, 1.0 / 3.0});
  return spaces;
}

/// Alternative names accepted by named(); each maps to a canonical name.
constexpr std::pair<std::string_view, std::string_view> kAliases[] = {{"rec709", "srgb-linear"}};

}  // namespace

RgbColourSpace::RgbColourSpace(std::string name, Chromaticity red, Chromaticity green, Chromaticity blue,
                               Chromaticity white)
    : name_(std::move(name)), red_(red), green_(green), blue_(blue), white_(white) {
  rgb_to_xyz_ = derive_rgb_to_xyz(name_, red, green, blue, white);
  xyz_to_rgb_ = rgb_to_xyz_.inverse();
}

const RgbColourSpace& RgbColourSpace::named(std::string_view name) {
  // Function-local static: built on first use, thread-safe (C++11 magic statics), no init-order coupling.
  static const std::vector<RgbColourSpace> spaces = make_built_in_spaces();
  for (const auto& [alias, canonical] : kAliases)
    if (name == alias) name = canonical;
  for (const RgbColourSpace& space : spaces)
    if (space.name() == name) return space;
  std::string known;
  for (const std::string& n : names()) known += (known.empty() ? "" : ", ") + n;
  for (const auto& [alias, canonical] : kAliases)
    known += ", " + std::string(alias) + " (= " + std::string(canonical) + ")";
  throw InputError({}, "unknown RGB colour space \"" + std::string(name) + "\"; known: " + known);
}

std::vector<std::string> RgbColourSpace::names() {
  return {"srgb-linear", "rec2020", "display-p3", "aces2065-1", "acescg", "cie-rgb"};
}

Xyz RgbColourSpace::to_xyz(const Rgb& rgb) const {
  const auto v = rgb_to_xyz_.apply(std::array<double, 3>{rgb.r, rgb.g, rgb.b});
  return {v[0], v[1], v[2]};
}

Rgb RgbColourSpace::from_xyz(const Xyz& xyz) const {
  const Xyz v = xyz_to_rgb_.apply(xyz);
  return {v.x, v.y, v.z};
}

// IEC 61966-2-1:1999 section 4.1 (decode, eq. 3-4) and 5.2 (encode). The published thresholds 0.04045 and
// 0.0031308 are each other's image only approximately: at 0.0031308 the two encode branches give 0.040449936
// and 0.040449907, a jump of 3e-8, harmless at any bit depth. Negative (out-of-gamut) inputs take the linear
// segment, so they stay finite and both functions stay monotonic.
double srgb_encode(double linear) {
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace rimu
