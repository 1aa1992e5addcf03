#include "transport/bsdfs/hair_bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/bsdfs/fresnel.h"
#include "spectral/math_constants.h"

namespace rimu {
namespace {


float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
float safe_asin(float x) { return std::asin(std::clamp(x, -1.0f, 1.0f)); }

// log I0(x), the modified Bessel function of the first kind, order 0, for x ≥ 0. The power series
// Σ (x²/4)^i / (i!)² summed to double precision up to x = 12 (pbrt stops at ten terms, which at x = 10 misses 0.3 %
// of I0 and so of the furnace); beyond, the asymptotic series e^x/√(2πx)·Σ_k c_k/x^k with
// c_k = ((2k−1)!!)²/(k! 8^k) to k = 4, whose next term is < 1e-6 there (Abramowitz & Stegun 9.7.1).
double log_bessel_i0(double x) {
  if (x > 12.0) {
    const double r = 1.0 / x;
    const double tail = r * (1.0 / 8.0 + r * (9.0 / 128.0 + r * (225.0 / 3072.0 + r * 11025.0 / 98304.0)));
    return x - 0.5 * std::log(2.0 * kPi * x) + std::log1p(tail);
  }
  // Mp is returned in float: terms below 1e-12 of the sum cannot change it. At x = 12 that is 30 terms; the
  // divisions by i² come from a table (a division per term was a third of eval()'s cost).
  static constexpr auto kInverseSquares = [] {
    std::array<double, 48> table{};
    for (size_t i = 1; i < table.size(); ++i) table[i] = 1.0 / (double(i) * double(i));
    return table;
  }();
  const double q = 0.25 * x * x;
  double term = 1.0, sum = 1.0;
  for (size_t i = 1; i < kInverseSquares.size() && term > 1e-12 * sum; ++i) {
    term *= q * kInverseSquares[i];
    sum += term;
  }
  return std::log(sum);
}

// log(2 v sinh(1/v)) = log v + 1/v + log(1 − e^(−2/v)), Mp's normalisation, without overflow at small v.
double log_longitudinal_norm(double v) { return std::log(v) + 1.0 / v + std::log1p(-std::exp(-2.0 / v)); }

// d'Eon et al. 2011's longitudinal scattering, normalised so that ∫ Mp cos θi dθi = 1 over [−π/2, π/2]:
//   Mp = exp(−sin θi sin θo / v) I0(cos θi cos θo / v) / (2 v sinh(1/v)),
// evaluated as one exponential of logs so that small variances (v ~ 1e-6 at β_m = 0.001) overflow neither the
// Bessel function nor sinh. `log_norm` = log_longitudinal_norm(v).
float longitudinal(float cos_i, float cos_o, float sin_i, float sin_o, float v, double log_norm) {
  const double a = double(cos_i) * cos_o / v, b = double(sin_i) * sin_o / v;
  return float(std::exp(log_bessel_i0(a) - b - log_norm));
}

// The logistic density of scale s and its CDF; trimmed to [−π, π] it is Np's shape in φ.
double logistic(double x, double s) {
  const double e = std::exp(-std::fabs(x) / s);
  return e / (s * (1.0 + e) * (1.0 + e));
}
double logistic_cdf(double x, double s) { return 1.0 / (1.0 + std::exp(-x / s)); }


// Inverts the trimmed CDF; the clamp absorbs log(0) at u = 0 or 1 when s is tiny.
double sample_trimmed_logistic(double u, double s) {
  const double low = logistic_cdf(-kPi, s), k = logistic_cdf(kPi, s) - low;
  const double x = -s * std::log(1.0 / (u * k + low) - 1.0);
  return std::clamp(std::isnan(x) ? 0.0 : x, -kPi, kPi);
}

// The azimuth at which lobe p leaves a smooth fibre (Marschner et al. 2003): Φ = 2pγt − 2γo + pπ.
double exit_azimuth(int p, double gamma_o, double gamma_t) { return 2.0 * p * gamma_t - 2.0 * gamma_o + p * kPi; }

// Np: the logistic trimmed to [−π, π] (`inverse_mass` = 1/(CDF(π) − CDF(−π))) around lobe p's exit azimuth.
double azimuthal(double phi, int p, double s, double inverse_mass, double gamma_o, double gamma_t) {
  return logistic(std::remainder(phi - exit_azimuth(p, gamma_o, gamma_t), 2.0 * kPi), s) * inverse_mass;
}

}  // namespace

struct HairBsdf::Incidence {
  Vec3 wo;  // fibre frame
  float sin_o, cos_o, phi_o, gamma_t;
  std::array<SampledSpectrum, kMaxP + 1> ap;
};

Vec2 hair_fibre_direction(const Frame& frame, Vec3 dpdu) {
  const Vec3 local = frame.to_local(dpdu);
  const float length = std::sqrt(local.x * local.x + local.y * local.y);
  if (!(length > 1e-12f) || !std::isfinite(length)) return {1.0f, 0.0f};
  return {local.x / length, local.y / length};
}

HairBsdf::HairBsdf(Vec2 fibre_direction, float h, SampledSpectrum sigma_a, const HairParameters& parameters)
    : x_(fibre_direction), h_(std::clamp(h, -1.0f, 1.0f)), gamma_o_(safe_asin(h_)), eta_(parameters.eta),
      sigma_a_(sigma_a) {
  // Chiang et al. 2016, Eqs. 7 and 8: the roughnesses mapped to Mp's variance and Np's logistic scale, fitted so
  // that β = 1 looks like a fully diffuse fibre. TT is narrower (v/4) and TRT and beyond wider (4v), after the
  // widths Marschner et al. measured.
  const float bm = parameters.beta_m, bn = parameters.beta_n;
  const float m = 0.726f * bm + 0.812f * bm * bm + 3.7f * std::pow(bm, 20.0f);
  variance_ = {m * m, 0.25f * m * m, 4.0f * m * m, 4.0f * m * m};
  logistic_scale_ = float(std::sqrt(kPi / 8.0)) * (0.265f * bn + 1.194f * bn * bn + 5.372f * std::pow(bn, 22.0f));
  // Per-BSDF constants of Mp and Np, so that eval() and pdf() pay only for what depends on the directions.
  for (size_t p = 0; p <= kMaxP; ++p) log_longitudinal_norm_[p] = log_longitudinal_norm(variance_[p]);
  logistic_inverse_mass_ = 1.0 / (logistic_cdf(kPi, logistic_scale_) - logistic_cdf(-kPi, logistic_scale_));
  // The tilt doubles per lobe: sin/cos of α, 2α, 4α by the double-angle formulas.
  sin_2k_alpha_[0] = std::sin(parameters.alpha_deg * float(kPi / 180.0));
  cos_2k_alpha_[0] = safe_sqrt(1.0f - sin_2k_alpha_[0] * sin_2k_alpha_[0]);
  for (int k = 1; k < 3; ++k) {
    sin_2k_alpha_[k] = 2.0f * cos_2k_alpha_[k - 1] * sin_2k_alpha_[k - 1];
    cos_2k_alpha_[k] = cos_2k_alpha_[k - 1] * cos_2k_alpha_[k - 1] - sin_2k_alpha_[k - 1] * sin_2k_alpha_[k - 1];
  }
}

HairBsdf::Incidence HairBsdf::incidence(Vec3 wo) const {
  Incidence in;
  in.wo = wo;
  in.sin_o = std::clamp(wo.x, -1.0f, 1.0f);
  in.cos_o = safe_sqrt(1.0f - in.sin_o * in.sin_o);
  in.phi_o = std::atan2(wo.z, wo.y);
  // Bravais' index η' = √(η² − sin²θo)/cos θo: refraction projected onto the normal plane behaves as a 2D
  // refraction with η'. At grazing θo it grows without bound (γt → 0); the floor on cos θo keeps it finite.
  const float sin_t = in.sin_o / eta_, cos_t = safe_sqrt(1.0f - sin_t * sin_t);
  const float eta_p = safe_sqrt(eta_ * eta_ - in.sin_o * in.sin_o) / std::max(in.cos_o, 1e-7f);
  const float sin_gamma_t = h_ / std::max(eta_p, 1.0f), cos_gamma_t = safe_sqrt(1.0f - sin_gamma_t * sin_gamma_t);
  in.gamma_t = safe_asin(sin_gamma_t);
  // One pass through the interior: the chord 2 cos γt of a unit-radius section, lengthened by 1/cos θt along
  // the fibre. The Fresnel reflectance at the surface uses the angle between wo and the surface normal there,
  // cos θo cos γo.
  const SampledSpectrum t = exp(-sigma_a_ * Float4(2.0f * cos_gamma_t / std::max(cos_t, 1e-7f)));
  const float f = fresnel_dielectric(in.cos_o * safe_sqrt(1.0f - h_ * h_), eta_);
  in.ap[0] = Float4(f);
  in.ap[1] = Float4((1.0f - f) * (1.0f - f)) * t;
  in.ap[2] = in.ap[1] * t * Float4(f);
  // p ≥ 3: the geometric series of further internal reflections, Σ_{p≥3} = A2·fT/(1 − fT). fT = 1 only where
  // f = 1 (grazing: wo along the fibre, or h = ±1), where A2 = 0 and so is the series.
  const SampledSpectrum ft = t * Float4(f), rest = Float4(1.0f) - ft;
  in.ap[3] = select(rest > Float4(0.0f), in.ap[2] * ft / select(rest > Float4(0.0f), rest, Float4(1.0f)), Float4(0.0f));
  return in;
}

void HairBsdf::tilted(int p, float sin_o, float cos_o, float& sin_op, float& cos_op) const {
  // R is shifted by −2α, TT by +α, TRT by +4α (the scales tilt the surface the light meets, Chiang et al. §4.1).
  if (p == 0) {
    sin_op = sin_o * cos_2k_alpha_[1] - cos_o * sin_2k_alpha_[1];
    cos_op = cos_o * cos_2k_alpha_[1] + sin_o * sin_2k_alpha_[1];
  } else if (p == 1) {
    sin_op = sin_o * cos_2k_alpha_[0] + cos_o * sin_2k_alpha_[0];
    cos_op = cos_o * cos_2k_alpha_[0] - sin_o * sin_2k_alpha_[0];
  } else if (p == 2) {
    sin_op = sin_o * cos_2k_alpha_[2] + cos_o * sin_2k_alpha_[2];
    cos_op = cos_o * cos_2k_alpha_[2] - sin_o * sin_2k_alpha_[2];
  } else {
    sin_op = sin_o;
    cos_op = cos_o;
  }
  cos_op = std::fabs(cos_op);  // a tilt past the pole folds back
}

std::array<float, HairBsdf::kMaxP + 1> HairBsdf::lobe_densities(const Incidence& in, Vec3 wi) const {
  const float sin_i = std::clamp(wi.x, -1.0f, 1.0f), cos_i = safe_sqrt(1.0f - sin_i * sin_i);
  const double phi = double(std::atan2(wi.z, wi.y)) - in.phi_o;
  std::array<float, kMaxP + 1> density;
  for (int p = 0; p < kMaxP; ++p) {
    float sin_op, cos_op;
    tilted(p, in.sin_o, in.cos_o, sin_op, cos_op);
    density[size_t(p)] =
        longitudinal(cos_i, cos_op, sin_i, sin_op, variance_[size_t(p)], log_longitudinal_norm_[size_t(p)]) *
        float(azimuthal(phi, p, logistic_scale_, logistic_inverse_mass_, gamma_o_, in.gamma_t));
  }
  // Longer paths: no tilt, uniform in φ.
  density[kMaxP] = longitudinal(cos_i, in.cos_o, sin_i, in.sin_o, variance_[kMaxP], log_longitudinal_norm_[kMaxP]) *
                   float(0.5 / kPi);
  return density;
}

std::array<SampledSpectrum, HairBsdf::kMaxP + 1> HairBsdf::attenuation(Vec3 wo) const {
  return incidence(to_fibre(wo)).ap;
}

namespace {
// Lane k's probability of sampling lobe p, A_p/ΣA (0 for a lane whose Ap all vanish: it could sample nothing).
std::array<SampledSpectrum, HairBsdf::kMaxP + 1> lobe_probabilities(
    const std::array<SampledSpectrum, HairBsdf::kMaxP + 1>& ap) {
  const SampledSpectrum total = ap[0] + ap[1] + ap[2] + ap[3];
  const Mask4 positive = total > Float4(0.0f);
  const SampledSpectrum inverse = select(positive, Float4(1.0f) / select(positive, total, Float4(1.0f)), Float4(0.0f));
  return {ap[0] * inverse, ap[1] * inverse, ap[2] * inverse, ap[3] * inverse};
}
}  // namespace

SampledSpectrum HairBsdf::eval(Vec3 wo, Vec3 wi) const {
  if (wi.z == 0.0f) return Float4(0.0f);
  const Incidence in = incidence(to_fibre(wo));
  const auto density = lobe_densities(in, to_fibre(wi));
  SampledSpectrum f(0.0f);
  for (int p = 0; p <= kMaxP; ++p) f += in.ap[size_t(p)] * Float4(density[size_t(p)]);
  // The floor keeps f finite at denormal cosines, where the integrator's |cos θi| then makes the product
  // slightly too small on a set of measure zero.
  return f / Float4(std::max(std::fabs(wi.z), 1e-20f));
}

SampledSpectrum HairBsdf::pdf(Vec3 wo, Vec3 wi) const {
  const Incidence in = incidence(to_fibre(wo));
  const auto density = lobe_densities(in, to_fibre(wi));
  const auto probability = lobe_probabilities(in.ap);
  SampledSpectrum pdf(0.0f);
  for (int p = 0; p <= kMaxP; ++p) pdf += probability[size_t(p)] * Float4(density[size_t(p)]);
  return pdf;
}

std::optional<BsdfSample> HairBsdf::sample(Vec3 wo_local, float u_lobe, Vec2 u) const {
  const Incidence in = incidence(to_fibre(wo_local));
  const auto probability = lobe_probabilities(in.ap);
  // Lobe p by the hero's Ap; the remainder of u_lobe, rescaled to [0, 1), then draws φ.
  int p = 0;
  float u_rest = u_lobe;
  while (p < kMaxP && u_rest >= probability[size_t(p)][0]) u_rest -= probability[size_t(p)][0], ++p;
  const float lobe_p = probability[size_t(p)][0];
  if (!(lobe_p > 0.0f)) return std::nullopt;  // the hero's Ap all vanish (η = 1 and σa = ∞): nothing to sample
  const double u_phi = std::clamp(double(u_rest) / lobe_p, 0.0, 1.0 - 1e-12);

  float sin_op, cos_op;
  tilted(p, in.sin_o, in.cos_o, sin_op, cos_op);
  // θi from Mp exactly (d'Eon 2013): cos θ' = 1 + v log(u + (1 − u) e^(−2/v)) about the mirror direction −θo',
  // then rotated by a uniform angle 2π u.y around the cone.
  const double v = variance_[size_t(p)];
  const double cos_cone = std::clamp(1.0 + v * std::log(u.x + (1.0 - u.x) * std::exp(-2.0 / v)), -1.0, 1.0);
  const double sin_cone = std::sqrt(std::max(0.0, 1.0 - cos_cone * cos_cone));
  const double sin_i = std::clamp(-cos_cone * sin_op + sin_cone * std::cos(2.0 * kPi * u.y) * cos_op, -1.0, 1.0);
  const double cos_i = std::sqrt(std::max(0.0, 1.0 - sin_i * sin_i));
  const double dphi = p < kMaxP ? exit_azimuth(p, gamma_o_, in.gamma_t) + sample_trimmed_logistic(u_phi, logistic_scale_)
                                : 2.0 * kPi * u_phi;
  const double phi_i = in.phi_o + dphi;
  const Vec3 wi = from_fibre({float(sin_i), float(cos_i * std::cos(phi_i)), float(cos_i * std::sin(phi_i))});
  if (wi.z == 0.0f) return std::nullopt;  // f divides by |wi.z|; the contract forbids a zero-pdf sample

  const auto density = lobe_densities(in, to_fibre(wi));
  BsdfSample s{wi, Float4(0.0f), Float4(0.0f)};
  for (int q = 0; q <= kMaxP; ++q) {
    s.f += in.ap[size_t(q)] * Float4(density[size_t(q)]);
    s.pdf += probability[size_t(q)] * Float4(density[size_t(q)]);
  }
  s.f = s.f / Float4(std::max(std::fabs(wi.z), 1e-20f));
  if (!(s.pdf[0] > 0.0f)) return std::nullopt;  // Mp or Np underflowed at a far tail
  return s;
}

SampledSpectrum HairBsdf::sigma_a_from_reflectance(SampledSpectrum reflectance, float beta_n) {
  // Chiang et al. 2016, Eq. 9: σa = (ln c / (5.969 − 0.215βn + 2.532βn² − 10.73βn³ + 5.574βn⁴ + 0.245βn⁵))²,
  // fitted to their simulations of many fibres.
  const float b = beta_n;
  const float denominator = 5.969f - 0.215f * b + 2.532f * b * b - 10.73f * b * b * b + 5.574f * b * b * b * b +
                            0.245f * b * b * b * b * b;
  const auto c = clamp(reflectance, Float4(1e-4f), Float4(1.0f)).to_array();
  SampledSpectrum sigma_a;
  for (int k = 0; k < kLaneCount; ++k) {
    const float r = std::log(c[size_t(k)]) / denominator;
    sigma_a.set(k, r * r);
  }
  return sigma_a;
}

}  // namespace rimu
