#include "transport/bsdfs/fresnel.h"

#include <algorithm>
#include <cmath>

#include "transport/bsdfs/simpson_rule.h"

namespace rimu {
namespace {

/// A complex number per lane; only what the conductor Fresnel equations need.
struct Complex4 {
  Float4 re, im;
};
Complex4 operator+(Complex4 a, Complex4 b) { return {a.re + b.re, a.im + b.im}; }
Complex4 operator-(Complex4 a, Complex4 b) { return {a.re - b.re, a.im - b.im}; }
Complex4 operator*(Complex4 a, Complex4 b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
Complex4 operator/(Complex4 a, Complex4 b) {
  const Float4 d = b.re * b.re + b.im * b.im;
  return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
}
Float4 norm2(Complex4 a) { return a.re * a.re + a.im * a.im; }
/// Principal square root: Re ≥ 0, and Im has the sign of the argument's Im.
Complex4 complex_sqrt(Complex4 z) {
  const Float4 modulus = sqrt(norm2(z));
  const Float4 re = sqrt(max(Float4(0.0f), (modulus + z.re) * Float4(0.5f)));
  const Float4 im_abs = sqrt(max(Float4(0.0f), (modulus - z.re) * Float4(0.5f)));
  return {re, select(z.im < Float4(0.0f), -im_abs, im_abs)};
}
/// |num|²/|den|², or 1 where the denominator vanishes (the grazing limit, reached only for η = 1).
Float4 ratio2(Complex4 num, Complex4 den) {
  const Float4 d = norm2(den);
  return select(d > Float4(0.0f), norm2(num) / d, Float4(1.0f));
}

}  // namespace

PolarisedReflectance fresnel_dielectric_polarised(SampledSpectrum cos_theta_i, SampledSpectrum eta) {
  const Mask4 inside = cos_theta_i < Float4(0.0f);
  const Float4 eta_rel = select(inside, Float4(1.0f) / eta, eta);  // n_t / n_i along this ray
  const Float4 cos_i = min(abs(cos_theta_i), Float4(1.0f));
  const Float4 sin2_t = (Float4(1.0f) - cos_i * cos_i) / (eta_rel * eta_rel);
  const Mask4 total_internal = sin2_t >= Float4(1.0f);
  const Float4 cos_t = sqrt(max(Float4(0.0f), Float4(1.0f) - sin2_t));
  // Both denominators are > 0 unless cos θi = cos θt = 0, which is the total-internal branch.
  const Float4 r_s = (cos_i - eta_rel * cos_t) / (cos_i + eta_rel * cos_t);
  const Float4 r_p = (eta_rel * cos_i - cos_t) / (eta_rel * cos_i + cos_t);
  return {select(total_internal, Float4(1.0f), r_s * r_s), select(total_internal, Float4(1.0f), r_p * r_p)};
}

SampledSpectrum fresnel_dielectric(SampledSpectrum cos_theta_i, SampledSpectrum eta) {
  const PolarisedReflectance r = fresnel_dielectric_polarised(cos_theta_i, eta);
  return Float4(0.5f) * (r.s + r.p);
}

namespace {

template <typename Real>
Real fresnel_dielectric_scalar(Real cos_theta_i, Real eta) {
  const Real eta_rel = cos_theta_i < 0 ? Real(1) / eta : eta;
  const Real cos_i = std::min(std::fabs(cos_theta_i), Real(1));
  const Real sin2_t = (Real(1) - cos_i * cos_i) / (eta_rel * eta_rel);
  if (sin2_t >= Real(1)) return Real(1);
  const Real cos_t = std::sqrt(Real(1) - sin2_t);
  // r_s = a/b and r_p = c/d as above; (r_s² + r_p²)/2 over one common denominator, one division instead of two
  // (the rough coat evaluates this at every event of its walk). b, d > 0 outside total internal reflection.
  const Real a = cos_i - eta_rel * cos_t, b = cos_i + eta_rel * cos_t;
  const Real c = eta_rel * cos_i - cos_t, d = eta_rel * cos_i + cos_t;
  return Real(0.5) * (a * a * d * d + c * c * b * b) / (b * b * d * d);
}

}  // namespace

float fresnel_dielectric(float cos_theta_i, float eta) { return fresnel_dielectric_scalar(cos_theta_i, eta); }
double fresnel_dielectric(double cos_theta_i, double eta) { return fresnel_dielectric_scalar(cos_theta_i, eta); }

SampledSpectrum fresnel_conductor(SampledSpectrum cos_theta_i, SampledSpectrum n, SampledSpectrum k) {
  const Float4 cos_i = clamp(cos_theta_i, Float4(0.0f), Float4(1.0f));
  const Complex4 eta{n, k};
  const Complex4 cos_i_c{cos_i, Float4(0.0f)};
  const Complex4 sin2_i{Float4(1.0f) - cos_i * cos_i, Float4(0.0f)};
  const Complex4 cos_t = complex_sqrt(Complex4{Float4(1.0f), Float4(0.0f)} - sin2_i / (eta * eta));
  const Complex4 eta_cos_t = eta * cos_t, eta_cos_i = eta * cos_i_c;
  const Float4 rs2 = ratio2(cos_i_c - eta_cos_t, cos_i_c + eta_cos_t);
  const Float4 rp2 = ratio2(eta_cos_i - cos_t, eta_cos_i + cos_t);
  return Float4(0.5f) * (rs2 + rp2);
}

double fresnel_diffuse_reflectance(double eta) {
  // 2∫ g(x) dx over [a, b] (composite Simpson, `intervals` even).
  const auto simpson = [](const auto& g, double a, double b, int intervals) {
    return 2.0 * simpson_integral(g, a, b, intervals);
  };
  // η ≥ 1: F(μ)·μ is smooth on [0, 1].
  if (eta >= 1.0) return simpson([eta](double mu) { return fresnel_dielectric(mu, eta) * mu; }, 0.0, 1.0, 512);
  // η < 1: total reflection below the critical cosine μc = √(1 − η²) contributes 2∫₀^μc μ dμ = μc². Above it,
  // F behaves like 1 − c√(μ − μc); the substitution μ = μc + t² makes the integrand smooth again.
  const double mu_critical = std::sqrt(1.0 - eta * eta);
  const auto smooth = [eta, mu_critical](double t) {
    const double mu = mu_critical + t * t;
    return fresnel_dielectric(mu, eta) * mu * 2.0 * t;
  };
  return mu_critical * mu_critical + simpson(smooth, 0.0, std::sqrt(1.0 - mu_critical), 512);
}

}  // namespace rimu
