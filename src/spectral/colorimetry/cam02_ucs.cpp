#include "spectral/colorimetry/cam02_ucs.h"

#include <cmath>
#include <numbers>

namespace rimu {
namespace {

// CIE 159:2004: the CAT02 matrix and the Hunt-Pointer-Estevez matrix (cone space of the compression step).
constexpr double kCat02[3][3] = {{0.7328, 0.4296, -0.1624}, {-0.7036, 1.6975, 0.0061}, {0.0030, 0.0136, 0.9834}};
constexpr double kHpe[3][3] = {{0.38971, 0.68898, -0.07868}, {-0.22981, 1.18340, 0.04641}, {0.0, 0.0, 1.0}};

void multiply(const double m[3][3], const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

/// Inverse of the CAT02 matrix (computed once, by cofactors).
struct Inverse3 {
  double m[3][3];
  explicit Inverse3(const double a[3][3]) {
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
        m[i][j] = (a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]) / det;
      }
  }
};

const Inverse3& cat02_inverse() {
  static const Inverse3 inverse(kCat02);
  return inverse;
}

/// The post-adaptation compression of CIE 159 eq. (7.x), odd in its argument for negative responses.
double compress(double response, double f_l) {
  const double p = std::pow(f_l * std::abs(response) / 100.0, 0.42);
  return std::copysign(400.0 * p / (27.13 + p), response) + 0.1;
}

}  // namespace

Cam02Ucs::Cam02Ucs(const Xyz& white, const Ciecam02Conditions& conditions) : c_(conditions), white_y_(white.y) {
  const double xyz_w[3] = {white.x, white.y, white.z};
  multiply(kCat02, xyz_w, white_rgb_);
  const double l_a = c_.adapting_luminance_cd_m2;
  const double k = 1.0 / (5.0 * l_a + 1.0);
  const double k4 = k * k * k * k;
  f_l_ = 0.2 * k4 * (5.0 * l_a) + 0.1 * (1.0 - k4) * (1.0 - k4) * std::cbrt(5.0 * l_a);
  n_ = c_.background_y / white.y;
  n_bb_ = 0.725 * std::pow(1.0 / n_, 0.2);
  z_ = 1.48 + std::sqrt(n_);
  // The achromatic response of the white, through the same path as any colour.
  const double d = c_.degree_of_adaptation;
  double adapted[3], hpe[3], tmp[3];
  for (int i = 0; i < 3; ++i) adapted[i] = (white.y * d / white_rgb_[i] + 1.0 - d) * white_rgb_[i];
  multiply(cat02_inverse().m, adapted, tmp);
  multiply(kHpe, tmp, hpe);
  const double ra = compress(hpe[0], f_l_), ga = compress(hpe[1], f_l_), ba = compress(hpe[2], f_l_);
  achromatic_white_ = (2.0 * ra + ga + ba / 20.0 - 0.305) * n_bb_;
}

Jab Cam02Ucs::jab(const Xyz& xyz) const {
  const double d = c_.degree_of_adaptation;
  const double v[3] = {xyz.x, xyz.y, xyz.z};
  double rgb[3], adapted[3], tmp[3], hpe[3];
  multiply(kCat02, v, rgb);
  // Von Kries in CAT02 space towards an equal-energy white of luminance Y_w (CIE 159 eq. 7.4).
  for (int i = 0; i < 3; ++i) adapted[i] = (white_y_ * d / white_rgb_[i] + 1.0 - d) * rgb[i];
  multiply(cat02_inverse().m, adapted, tmp);
  multiply(kHpe, tmp, hpe);
  const double ra = compress(hpe[0], f_l_), ga = compress(hpe[1], f_l_), ba = compress(hpe[2], f_l_);

  const double a = ra - 12.0 * ga / 11.0 + ba / 11.0;
  const double b = (ra + ga - 2.0 * ba) / 9.0;
  const double h_rad = std::atan2(b, a);
  const double e_t = 0.25 * (std::cos(h_rad + 2.0) + 3.8);
  const double achromatic = (2.0 * ra + ga + ba / 20.0 - 0.305) * n_bb_;
  const double j = 100.0 * std::pow(achromatic / achromatic_white_, c_.surround_c * z_);
  const double n_cb = n_bb_;
  const double t = (50000.0 / 13.0 * c_.surround_nc * n_cb * e_t * std::hypot(a, b)) / (ra + ga + 21.0 / 20.0 * ba);
  const double chroma = std::pow(t, 0.9) * std::sqrt(j / 100.0) * std::pow(1.64 - std::pow(0.29, n_), 0.73);
  const double colourfulness = chroma * std::pow(f_l_, 0.25);
  // CAM02-UCS (Luo, Cui & Li 2006): J' = 1.7 J / (1 + 0.007 J), M' = ln(1 + 0.0228 M) / 0.0228.
  const double j_ucs = 1.7 * j / (1.0 + 0.007 * j);
  const double m_ucs = std::log1p(0.0228 * colourfulness) / 0.0228;
  return {j_ucs, m_ucs * std::cos(h_rad), m_ucs * std::sin(h_rad)};
}

}  // namespace rimu
