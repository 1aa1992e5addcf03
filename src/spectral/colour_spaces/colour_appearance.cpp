#include "spectral/colour_spaces/colour_appearance.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "spectral/colour_spaces/chromatic_adaptation.h"
#include "spectral/colorimetry/cielab.h"

namespace rimu {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// CIE 159:2004 eq. 7.x: the Hunt-Pointer-Estevez matrix, CIECAM02's space for the compression.
const Matrix3 kHuntPointerEstevez{{{{0.38971, 0.68898, -0.07868}, {-0.22981, 1.18340, 0.04641}, {0.0, 0.0, 1.0}}}};

// The post-adaptation compression, odd in its argument (CIE 159 eq. 7.10 with the sign rule of Li et al. 2017).
double compress(double response, double f_l) {
  const double p = std::pow(f_l * std::abs(response) / 100.0, 0.42);
  return std::copysign(400.0 * p / (27.13 + p), response) + 0.1;
}
// Its inverse.
double decompress(double compressed, double f_l) {
  const double x = compressed - 0.1;
  const double ax = std::abs(x);
  return std::copysign(100.0 / f_l * std::pow(27.13 * ax / (400.0 - ax), 1.0 / 0.42), x);
}

// Hue quadrature (CIE 159 Table 2): the unique hues' angles, eccentricities and quadratures.
constexpr double kHueAngle[5] = {20.14, 90.00, 164.25, 237.53, 380.14};
constexpr double kHueEccentricity[5] = {0.8, 0.7, 1.0, 1.2, 0.8};
constexpr double kHueQuadrature[5] = {0.0, 100.0, 200.0, 300.0, 400.0};

double hue_quadrature(double h_deg) {
  const double h = h_deg < kHueAngle[0] ? h_deg + 360.0 : h_deg;
  int i = 0;
  while (i < 3 && h >= kHueAngle[i + 1]) ++i;
  const double below = (h - kHueAngle[i]) / kHueEccentricity[i];
  const double above = (kHueAngle[i + 1] - h) / kHueEccentricity[i + 1];
  return kHueQuadrature[i] + 100.0 * below / (below + above);
}

double eccentricity(double h_deg) { return 0.25 * (std::cos(h_deg * kDeg + 2.0) + 3.8); }

}  // namespace

Surround surround_option(const std::string& name, const SourceLocation& where) {
  if (name == "average") return Surround::average();
  if (name == "dim") return Surround::dim();
  if (name == "dark") return Surround::dark();
  throw InputError(where, "expected a surround of average, dim or dark, got '" + name + "'");
}

ColourAppearanceModel::ColourAppearanceModel(AppearanceModel model, const ViewingConditions& conditions)
    : model_(model), v_(conditions) {
  to_adaptation_ = cone_response_matrix(model == AppearanceModel::cam16 ? CatMethod::cat16 : CatMethod::cat02);
  from_adaptation_ = to_adaptation_.inverse();
  if (model == AppearanceModel::ciecam02) {
    adapted_to_compression_ = kHuntPointerEstevez * from_adaptation_;
    compression_to_adapted_ = adapted_to_compression_.inverse();
  } else {
    adapted_to_compression_ = compression_to_adapted_ = Matrix3::identity();
  }
  const double l_a = v_.adapting_luminance_cd_m2;
  d_ = v_.degree_of_adaptation.value_or(
      std::clamp(v_.surround.f * (1.0 - std::exp((-l_a - 42.0) / 92.0) / 3.6), 0.0, 1.0));
  const Xyz w = v_.white;
  const Xyz rgb_w = to_adaptation_.apply(w);
  const double rgb_w_a[3] = {rgb_w.x, rgb_w.y, rgb_w.z};
  for (int i = 0; i < 3; ++i) d_rgb_[i] = d_ * w.y / rgb_w_a[i] + 1.0 - d_;
  const double k = 1.0 / (5.0 * l_a + 1.0), k4 = k * k * k * k;
  f_l_ = 0.2 * k4 * (5.0 * l_a) + 0.1 * (1.0 - k4) * (1.0 - k4) * std::cbrt(5.0 * l_a);
  n_ = v_.background_y / w.y;
  n_bb_ = 0.725 * std::pow(1.0 / n_, 0.2);
  z_ = 1.48 + std::sqrt(n_);
  const auto white = compressed_responses(w);
  achromatic_white_ = (2.0 * white[0] + white[1] + white[2] / 20.0 - 0.305) * n_bb_;
}

std::array<double, 3> ColourAppearanceModel::compressed_responses(const Xyz& xyz) const {
  const Xyz rgb = to_adaptation_.apply(xyz);
  const Xyz adapted{d_rgb_[0] * rgb.x, d_rgb_[1] * rgb.y, d_rgb_[2] * rgb.z};
  const Xyz cone = adapted_to_compression_.apply(adapted);
  return {compress(cone.x, f_l_), compress(cone.y, f_l_), compress(cone.z, f_l_)};
}

Appearance ColourAppearanceModel::forward(const Xyz& xyz) const {
  const auto [ra, ga, ba] = compressed_responses(xyz);
  const double a = ra - 12.0 * ga / 11.0 + ba / 11.0;
  const double b = (ra + ga - 2.0 * ba) / 9.0;
  Appearance out;
  out.h_deg = hue_angle_deg(b, a);
  const double achromatic = (2.0 * ra + ga + ba / 20.0 - 0.305) * n_bb_;
  // A black colour gives A slightly below A_w·0 (the 0.1 offsets): J is 0 there, never NaN.
  out.j = 100.0 * std::pow(std::max(0.0, achromatic / achromatic_white_), v_.surround.c * z_);
  out.q = 4.0 / v_.surround.c * std::sqrt(out.j / 100.0) * (achromatic_white_ + 4.0) * std::pow(f_l_, 0.25);
  const double t = 50000.0 / 13.0 * v_.surround.n_c * n_bb_ * eccentricity(out.h_deg) * std::hypot(a, b) /
                   (ra + ga + 21.0 / 20.0 * ba);
  out.c = std::pow(std::max(0.0, t), 0.9) * std::sqrt(out.j / 100.0) * std::pow(1.64 - std::pow(0.29, n_), 0.73);
  out.m = out.c * std::pow(f_l_, 0.25);
  out.s = out.q > 0.0 ? 100.0 * std::sqrt(out.m / out.q) : 0.0;
  out.hue_quadrature = hue_quadrature(out.h_deg);
  return out;
}

Xyz ColourAppearanceModel::inverse(double j, double m, double h_deg) const {
  const double c = m / std::pow(f_l_, 0.25);
  const double j_ratio = std::max(0.0, j) / 100.0;
  const double t =
      j_ratio > 0.0 ? std::pow(c / (std::sqrt(j_ratio) * std::pow(1.64 - std::pow(0.29, n_), 0.73)), 1.0 / 0.9) : 0.0;
  const double achromatic = achromatic_white_ * std::pow(j_ratio, 1.0 / (v_.surround.c * z_));
  const double p2 = achromatic / n_bb_ + 0.305, p3 = 21.0 / 20.0;
  const double h = h_deg * kDeg, sin_h = std::sin(h), cos_h = std::cos(h);
  double a = 0.0, b = 0.0;
  if (t > 0.0) {  // CIE 159:2004 §8 step 3, with whichever of sin h, cos h is larger as the divisor
    const double p1 = 50000.0 / 13.0 * v_.surround.n_c * n_bb_ * eccentricity(h_deg) / t;
    if (std::abs(sin_h) >= std::abs(cos_h)) {
      const double p4 = p1 / sin_h;
      b = p2 * (2.0 + p3) * (460.0 / 1403.0) /
          (p4 + (2.0 + p3) * (220.0 / 1403.0) * (cos_h / sin_h) - 27.0 / 1403.0 + p3 * (6300.0 / 1403.0));
      a = b * cos_h / sin_h;
    } else {
      const double p5 = p1 / cos_h;
      a = p2 * (2.0 + p3) * (460.0 / 1403.0) /
          (p5 + (2.0 + p3) * (220.0 / 1403.0) - (27.0 / 1403.0 - p3 * (6300.0 / 1403.0)) * (sin_h / cos_h));
      b = a * sin_h / cos_h;
    }
  }
  const double ra = (460.0 * p2 + 451.0 * a + 288.0 * b) / 1403.0;
  const double ga = (460.0 * p2 - 891.0 * a - 261.0 * b) / 1403.0;
  const double ba = (460.0 * p2 - 220.0 * a - 6300.0 * b) / 1403.0;
  const Xyz cone{decompress(ra, f_l_), decompress(ga, f_l_), decompress(ba, f_l_)};
  const Xyz adapted = compression_to_adapted_.apply(cone);
  return from_adaptation_.apply(Xyz{adapted.x / d_rgb_[0], adapted.y / d_rgb_[1], adapted.z / d_rgb_[2]});
}

Jab ColourAppearanceModel::ucs_of(const Appearance& appearance) {
  const double j = 1.7 * appearance.j / (1.0 + 0.007 * appearance.j);
  const double m = std::log1p(0.0228 * appearance.m) / 0.0228;
  return {j, m * std::cos(appearance.h_deg * kDeg), m * std::sin(appearance.h_deg * kDeg)};
}

Appearance ColourAppearanceModel::appearance_of_ucs(const Jab& jab) {
  Appearance out;
  out.j = jab.j / (1.7 - 0.007 * jab.j);
  out.m = std::expm1(0.0228 * std::hypot(jab.a, jab.b)) / 0.0228;
  out.h_deg = hue_angle_deg(jab.b, jab.a);
  return out;
}

}  // namespace rimu
