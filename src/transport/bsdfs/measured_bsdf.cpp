#include "transport/bsdfs/measured_bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rimu {

namespace {

struct Angles {
  float theta, phi;
};
Angles angles_of(Vec3 w) {
  return {std::acos(std::clamp(w.z, -1.0f, 1.0f)), std::atan2(w.y, w.x)};
}

// The Jacobian from the half vector's square to ωi: dωm/du of the square's map to the sphere (θ = π u_θ²/2,
// φ = 2π u_φ − π), 2π² u_θ sin θm, kept from 0 as pbrt-v4 keeps it, times dωi/dωm = 4 ωo·ωm of reflection.
float square_to_incident_jacobian(Vec3 wo, Vec3 wm, float u_theta, float sin_theta_m) {
  constexpr float pi = std::numbers::pi_v<float>;
  return 4.0f * dot(wo, wm) * std::max(2.0f * pi * pi * u_theta * sin_theta_m, 1e-6f);
}

}  // namespace

SampledSpectrum MeasuredBsdf::spectral_factor(Vec2 u, float phi_o, float theta_o) const {
  const float leading[2] = {phi_o, theta_o};
  const std::array<float, 4> lambda = {lambda_nm_[0], lambda_nm_[1], lambda_nm_[2], lambda_nm_[3]};
  const std::array<float, 4> s = brdf_->spectra().values_along_last(u, leading, lambda);
  return max(Float4(s[0], s[1], s[2], s[3]), Float4(0.0f));
}

float MeasuredBsdf::microfacet_factor(Vec2 u_wm, Vec2 u_wo, float cos_theta_i) const {
  const float sigma = brdf_->sigma().value(u_wo, {});
  if (!(sigma > 0.0f) || !(cos_theta_i > 0.0f)) return 0.0f;
  return brdf_->ndf().value(u_wm, {}) / (4.0f * sigma * cos_theta_i);
}

std::optional<MeasuredBsdf::Pair> MeasuredBsdf::pair_of(Vec3 wo, Vec3 wi) const {
  if (wo.z < 0.0f) {  // the back: both directions turned through the origin, as pbrt-v4 turns them
    wo = -wo;
    wi = -wi;
  }
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return std::nullopt;
  const Vec3 sum = wo + wi;
  if (length_squared(sum) == 0.0f) return std::nullopt;
  Pair pair;
  pair.wo = wo;
  pair.wi = wi;
  pair.wm = normalize(sum);
  const Angles o = angles_of(wo), m = angles_of(pair.wm);
  pair.phi_o = o.phi;
  pair.theta_o = o.theta;
  float u_phi_m = MeasuredBrdf::phi_to_u(brdf_->isotropic() ? m.phi - o.phi : m.phi);
  u_phi_m -= std::floor(u_phi_m);
  pair.u_wm = {MeasuredBrdf::theta_to_u(m.theta), u_phi_m};
  const float parameters[2] = {o.phi, o.theta};
  pair.vndf = brdf_->vndf().invert(pair.u_wm, parameters);
  return pair;
}

SampledSpectrum MeasuredBsdf::eval(Vec3 wo, Vec3 wi) const {
  const auto pair = pair_of(wo, wi);
  if (!pair) return Float4(0.0f);
  const Vec2 u_wo{MeasuredBrdf::theta_to_u(pair->theta_o), MeasuredBrdf::phi_to_u(pair->phi_o)};
  return spectral_factor(pair->vndf.p, pair->phi_o, pair->theta_o) *
         Float4(microfacet_factor(pair->u_wm, u_wo, pair->wi.z));
}

SampledSpectrum MeasuredBsdf::pdf(Vec3 wo, Vec3 wi) const {
  const auto pair = pair_of(wo, wi);
  if (!pair) return Float4(0.0f);
  const float parameters[2] = {pair->phi_o, pair->theta_o};
  const float luminance_density = brdf_->luminance().density(pair->vndf.p, parameters);
  const Vec3 wm = pair->wm;
  const float sin_theta_m = std::sqrt(wm.x * wm.x + wm.y * wm.y);
  const float jacobian = square_to_incident_jacobian(pair->wo, wm, pair->u_wm.x, sin_theta_m);
  const float density = pair->vndf.density * luminance_density / jacobian;
  return Float4(std::isfinite(density) ? density : 0.0f);
}

std::optional<BsdfSample> MeasuredBsdf::sample(Vec3 wo, float /*u_lobe*/, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  const bool back = wo.z < 0.0f;
  if (back) wo = -wo;
  const Angles o = angles_of(wo);
  const float parameters[2] = {o.phi, o.theta};

  // u → (luminance warp) → the visible-normal table's square → (vndf warp) → ωm's square.
  const BilinearWarp2D::Sample by_luminance = brdf_->luminance().sample(u, parameters);
  const BilinearWarp2D::Sample by_vndf = brdf_->vndf().sample(by_luminance.p, parameters);
  const Vec2 u_wm = by_vndf.p;
  const float theta_m = MeasuredBrdf::u_to_theta(u_wm.x);
  float phi_m = MeasuredBrdf::u_to_phi(u_wm.y);
  if (brdf_->isotropic()) phi_m += o.phi;
  const float sin_theta_m = std::sin(theta_m);
  const Vec3 wm{sin_theta_m * std::cos(phi_m), sin_theta_m * std::sin(phi_m), std::cos(theta_m)};
  const Vec3 wi = reflect(wo, wm);
  if (!(wi.z > 0.0f)) return std::nullopt;

  const Vec2 u_wo{MeasuredBrdf::theta_to_u(o.theta), MeasuredBrdf::phi_to_u(o.phi)};
  const SampledSpectrum f = spectral_factor(by_luminance.p, o.phi, o.theta) * Float4(microfacet_factor(u_wm, u_wo, wi.z));
  const float jacobian = square_to_incident_jacobian(wo, wm, u_wm.x, sin_theta_m);
  const float density = by_luminance.density * by_vndf.density / jacobian;
  if (!(density > 0.0f) || !std::isfinite(density)) return std::nullopt;
  return BsdfSample{back ? -wi : wi, f, Float4(density)};
}

}  // namespace rimu
