#include "spectral/colorimetry/delta_e.h"

#include <cmath>
#include <numbers>

namespace rimu {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

/// √(C⁷ / (C⁷ + 25⁷)): the chroma weighting that appears in both G and R_C of Sharma et al.
double chroma_weight(double chroma) {
  const double c7 = std::pow(chroma, 7.0);
  constexpr double k25_pow7 = 6103515625.0;  // 25⁷
  return std::sqrt(c7 / (c7 + k25_pow7));
}

}  // namespace

double delta_e_1976(const Lab& p, const Lab& q) {
  return std::sqrt((p.l - q.l) * (p.l - q.l) + (p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b));
}

double delta_e_2000(const Lab& p, const Lab& q, const Ciede2000Factors& k) {
  // Step 1 of Sharma et al. (2005): stretch a* by 1 + G so that near-neutral colours, whose hue the
  // CIELAB a* axis exaggerates, get their chroma and hue from (a', b).
  const double mean_chroma_ab = 0.5 * (std::hypot(p.a, p.b) + std::hypot(q.a, q.b));
  const double g = 0.5 * (1.0 - chroma_weight(mean_chroma_ab));
  const double a1 = (1.0 + g) * p.a;
  const double a2 = (1.0 + g) * q.a;
  const double c1 = std::hypot(a1, p.b);
  const double c2 = std::hypot(a2, q.b);
  // h' = atan2(b, a') in [0°, 360°), and 0 when a' = b = 0 (hue_angle_deg handles both).
  const double h1 = hue_angle_deg(p.b, a1);
  const double h2 = hue_angle_deg(q.b, a2);

  // Step 2: differences. The hue difference takes the short way round the circle; when either
  // colour is neutral (C'1·C'2 = 0) its hue is meaningless and Δh' is defined as 0.
  const double delta_l = q.l - p.l;
  const double delta_c = c2 - c1;
  const bool either_neutral = c1 * c2 == 0.0;
  double delta_h_deg = 0.0;
  if (!either_neutral) {
    delta_h_deg = h2 - h1;
    if (delta_h_deg > 180.0)
      delta_h_deg -= 360.0;
    else if (delta_h_deg < -180.0)
      delta_h_deg += 360.0;
  }
  const double delta_big_h = 2.0 * std::sqrt(c1 * c2) * std::sin(0.5 * delta_h_deg * kDegToRad);

  // Step 3: means and weighting functions. The mean hue, like Δh', is taken on the short arc, and the branch on
  // h'1 + h'2 < 360 keeps h̄' in [0°, 360°). The paper's note for a neutral colour is h̄' = h'1 + h'2 (the other
  // colour's hue, since the neutral's is 0), not the half-sum; it only changes the intermediate h̄', because
  // with a neutral ΔH' = 0 and h̄' enters ΔE00 only through terms multiplied by ΔH'.
  const double mean_l = 0.5 * (p.l + q.l);
  const double mean_c = 0.5 * (c1 + c2);
  double mean_h_deg = h1 + h2;
  if (!either_neutral) {
    if (std::abs(h1 - h2) <= 180.0)
      mean_h_deg = 0.5 * (h1 + h2);
    else if (h1 + h2 < 360.0)
      mean_h_deg = 0.5 * (h1 + h2 + 360.0);
    else
      mean_h_deg = 0.5 * (h1 + h2 - 360.0);
  }
  const double t =
      1.0 - 0.17 * std::cos((mean_h_deg - 30.0) * kDegToRad) + 0.24 * std::cos(2.0 * mean_h_deg * kDegToRad) +
      0.32 * std::cos((3.0 * mean_h_deg + 6.0) * kDegToRad) - 0.20 * std::cos((4.0 * mean_h_deg - 63.0) * kDegToRad);
  const double delta_theta_deg = 30.0 * std::exp(-std::pow((mean_h_deg - 275.0) / 25.0, 2.0));
  const double r_c = 2.0 * chroma_weight(mean_c);
  const double l_minus_50_sq = (mean_l - 50.0) * (mean_l - 50.0);
  const double s_l = 1.0 + 0.015 * l_minus_50_sq / std::sqrt(20.0 + l_minus_50_sq);
  const double s_c = 1.0 + 0.045 * mean_c;
  const double s_h = 1.0 + 0.015 * mean_c * t;
  // The rotation term couples chroma and hue differences in the blue region (h̄' near 275°).
  const double r_t = -std::sin(2.0 * delta_theta_deg * kDegToRad) * r_c;

  const double term_l = delta_l / (k.k_l * s_l);
  const double term_c = delta_c / (k.k_c * s_c);
  const double term_h = delta_big_h / (k.k_h * s_h);
  return std::sqrt(term_l * term_l + term_c * term_c + term_h * term_h + r_t * term_c * term_h);
}

}  // namespace rimu
