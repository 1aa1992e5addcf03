#include "transport/lights/sky/cie_standard_sky.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace rimu {
namespace {

// CIE S 011/E:2003 Table 1: the gradation groups I-VI and indicatrix groups 1-6, and which pair each type uses.
struct Gradation {
  double a, b;
};
struct Indicatrix {
  double c, d, e;
};
constexpr Gradation kGradation[6] = {{4.0, -0.70}, {1.1, -0.8}, {0.0, -1.0}, {-1.0, -0.55}, {-1.0, -0.32}, {-1.0, -0.15}};
constexpr Indicatrix kIndicatrix[6] = {{0.0, -1.0, 0.0},  {2.0, -1.5, 0.15},  {5.0, -2.5, 0.30},
                                       {10.0, -3.0, 0.45}, {16.0, -3.0, 0.30}, {24.0, -2.8, 0.15}};
constexpr int kGroups[kCieSkyTypeCount][2] = {{1, 1}, {1, 2}, {2, 1}, {2, 2}, {3, 1}, {3, 2}, {3, 3}, {3, 4},
                                              {4, 2}, {4, 3}, {4, 4}, {5, 4}, {5, 5}, {6, 5}, {6, 6}};

constexpr const char* kDescriptions[kCieSkyTypeCount] = {
    "CIE standard overcast sky, steep luminance gradation towards zenith, azimuthal uniformity",
    "overcast, with steep luminance gradation and slight brightening towards the sun",
    "overcast, moderately graded with azimuthal uniformity",
    "overcast, moderately graded and slight brightening towards the sun",
    "sky of uniform luminance",
    "partly cloudy sky, no gradation towards zenith, slight brightening towards the sun",
    "partly cloudy sky, no gradation towards zenith, brighter circumsolar region",
    "partly cloudy sky, no gradation towards zenith, distinct solar corona",
    "partly cloudy, with the obscured sun",
    "partly cloudy, with brighter circumsolar region",
    "white-blue sky with distinct solar corona",
    "CIE standard clear sky, low luminance turbidity",
    "CIE standard clear sky, polluted atmosphere",
    "cloudless turbid sky with broad solar corona",
    "white-blue turbid sky with broad solar corona"};

constexpr std::array<CieSkyParameters, kCieSkyTypeCount> make_table() {
  std::array<CieSkyParameters, kCieSkyTypeCount> table{};
  for (int t = 0; t < kCieSkyTypeCount; ++t) {
    const Gradation g = kGradation[kGroups[t][0] - 1];
    const Indicatrix i = kIndicatrix[kGroups[t][1] - 1];
    table[t] = {g.a, g.b, i.c, i.d, i.e, kGroups[t][0], kGroups[t][1]};
  }
  return table;
}
constexpr std::array<CieSkyParameters, kCieSkyTypeCount> kTable = make_table();

}  // namespace

const CieSkyParameters& cie_sky_parameters(int type) {
  assert(type >= 1 && type <= kCieSkyTypeCount);
  return kTable[size_t(type - 1)];
}

const char* cie_sky_description(int type) {
  assert(type >= 1 && type <= kCieSkyTypeCount);
  return kDescriptions[type - 1];
}

double cie_gradation(const CieSkyParameters& p, double cos_zenith) {
  // b < 0 for every type, so exp(b / cos Z) → 0 as cos Z → 0⁺: the horizon's value is the limit 1.
  if (!(cos_zenith > 0.0)) return 1.0;
  return 1.0 + p.a * std::exp(p.b / cos_zenith);
}

double cie_indicatrix(const CieSkyParameters& p, double chi_rad) {
  const double cos_chi = std::cos(chi_rad);
  return 1.0 + p.c * (std::exp(p.d * chi_rad) - std::exp(p.d * std::numbers::pi / 2.0)) + p.e * cos_chi * cos_chi;
}

double cie_relative_luminance(const CieSkyParameters& p, double zenith_rad, double azimuth_from_sun_rad,
                              double sun_zenith_rad) {
  const double cos_chi = std::cos(sun_zenith_rad) * std::cos(zenith_rad) +
                         std::sin(sun_zenith_rad) * std::sin(zenith_rad) * std::cos(std::fabs(azimuth_from_sun_rad));
  const double chi = std::acos(std::clamp(cos_chi, -1.0, 1.0));
  return cie_indicatrix(p, chi) * cie_gradation(p, std::cos(zenith_rad)) /
         (cie_indicatrix(p, sun_zenith_rad) * cie_gradation(p, 1.0));
}

double cie_relative_luminance(const CieSkyParameters& p, const std::array<double, 3>& element,
                              const std::array<double, 3>& sun) {
  return CieSkyLuminance(p, sun)(element);
}

CieSkyLuminance::CieSkyLuminance(const CieSkyParameters& p, const std::array<double, 3>& sun)
    : p_(p), sun_(sun), exp_d_half_pi_(std::exp(p.d * std::numbers::pi / 2.0)) {
  const double sun_zenith = std::atan2(std::hypot(sun[0], sun[1]), sun[2]);
  inverse_zenith_ = 1.0 / (cie_indicatrix(p, sun_zenith) * cie_gradation(p, 1.0));
}

double CieSkyLuminance::operator()(const std::array<double, 3>& element) const {
  if (!(element[2] > 0.0)) return 0.0;
  const double cos_chi = element[0] * sun_[0] + element[1] * sun_[1] + element[2] * sun_[2];
  // χ by atan2 of |e × s| and e·s: acos loses half its digits near the sun, where the clear sky's indicatrix is steep.
  const double cx = element[1] * sun_[2] - element[2] * sun_[1], cy = element[2] * sun_[0] - element[0] * sun_[2],
               cz = element[0] * sun_[1] - element[1] * sun_[0];
  const double chi = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), cos_chi);
  // The indicatrix without its cos²χ's trigonometry: cos²χ from the (normalised) dot product.
  const double cos2_chi = cos_chi * cos_chi / (cos_chi * cos_chi + cx * cx + cy * cy + cz * cz);
  const double indicatrix = p_.c == 0.0 && p_.e == 0.0
                                ? 1.0
                                : 1.0 + p_.c * (std::exp(p_.d * chi) - exp_d_half_pi_) + p_.e * cos2_chi;
  return indicatrix * (1.0 + p_.a * std::exp(p_.b / element[2])) * inverse_zenith_;
}

}  // namespace rimu
