#include "spectral/colorimetry/delta_e_94_cmc.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rimu {
namespace {

// ΔH² from the Cartesian differences: Δa² + Δb² − ΔC² (never below 0; rounding can take it there for neutrals).
double delta_h_squared(const Lab& reference, const Lab& sample, double delta_c) {
  const double da = reference.a - sample.a, db = reference.b - sample.b;
  return std::max(0.0, da * da + db * db - delta_c * delta_c);
}

}  // namespace

double delta_e_1994(const Lab& reference, const Lab& sample, const Cie94Factors& f) {
  const double c_ref = std::hypot(reference.a, reference.b), c_sample = std::hypot(sample.a, sample.b);
  const double delta_l = reference.l - sample.l, delta_c = c_ref - c_sample;
  const double s_c = 1.0 + f.k1 * c_ref, s_h = 1.0 + f.k2 * c_ref;  // S_L = 1
  const double tl = delta_l / f.k_l, tc = delta_c / (f.k_c * s_c);
  return std::sqrt(tl * tl + tc * tc + delta_h_squared(reference, sample, delta_c) / (f.k_h * f.k_h * s_h * s_h));
}

double delta_e_cmc(const Lab& reference, const Lab& sample, double l, double c) {
  const double c_ref = std::hypot(reference.a, reference.b), c_sample = std::hypot(sample.a, sample.b);
  const double h_ref = hue_angle_deg(reference.b, reference.a);
  const double s_l = reference.l < 16.0 ? 0.511 : 0.040975 * reference.l / (1.0 + 0.01765 * reference.l);
  const double s_c = 0.0638 * c_ref / (1.0 + 0.0131 * c_ref) + 0.638;
  const double to_rad = std::numbers::pi / 180.0;
  const double t = (h_ref >= 164.0 && h_ref <= 345.0) ? 0.56 + std::abs(0.2 * std::cos((h_ref + 168.0) * to_rad))
                                                      : 0.36 + std::abs(0.4 * std::cos((h_ref + 35.0) * to_rad));
  const double c4 = c_ref * c_ref * c_ref * c_ref;
  const double f = std::sqrt(c4 / (c4 + 1900.0));
  const double s_h = s_c * (f * t + 1.0 - f);
  const double delta_l = reference.l - sample.l, delta_c = c_ref - c_sample;
  const double tl = delta_l / (l * s_l), tc = delta_c / (c * s_c);
  return std::sqrt(tl * tl + tc * tc + delta_h_squared(reference, sample, delta_c) / (s_h * s_h));
}

}  // namespace rimu
