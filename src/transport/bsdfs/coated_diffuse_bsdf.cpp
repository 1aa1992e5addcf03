#include "transport/bsdfs/coated_diffuse_bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/sampling/direction_warps.h"
#include "transport/bsdfs/fresnel.h"
#include "transport/bsdfs/simpson_rule.h"
#include "transport/geometry/frame.h"

namespace rimu {
CoatedDiffuseBsdf::CoatedDiffuseBsdf(SampledSpectrum albedo, SampledSpectrum eta,
                                     SampledSpectrum diffuse_fresnel_external)
    : albedo_(albedo), eta_(eta) {
  const Float4 eta2 = eta * eta;
  // Reciprocity of the interface for diffuse flux: (1 − F̄_int) η² = 1 − F̄_ext.
  const Float4 internal = Float4(1.0f) - (Float4(1.0f) - diffuse_fresnel_external) / eta2;
  diffuse_scale_ = albedo * Float4(std::numbers::inv_pi_v<float>) / (eta2 * (Float4(1.0f) - albedo * internal));
  mean_albedo_ = std::max(0.25f * sum(albedo), 0.05f);
}

CoatedDiffuseBsdf CoatedDiffuseBsdf::absorbing(SampledSpectrum albedo, SampledSpectrum eta,
                                                SampledSpectrum internal_reflectance, float thickness) {
  CoatedDiffuseBsdf b;
  b.albedo_ = albedo;
  b.eta_ = eta;
  b.diffuse_scale_ = albedo * Float4(std::numbers::inv_pi_v<float>) / (eta * eta * (Float4(1.0f) - albedo * internal_reflectance));
  b.mean_albedo_ = std::max(0.25f * sum(albedo), 0.05f);
  b.thickness_ = std::max(thickness, 0.0f);
  return b;
}

SampledSpectrum CoatedDiffuseBsdf::crossing(float cos_theta) const {
  const Float4 transmit = Float4(1.0f) - fresnel_dielectric(Float4(cos_theta), eta_);
  if (thickness_ == 0.0f) return transmit;
  // cos θt from Snell's law, per lane: μt² = 1 − sin²θ/η².
  const Float4 mu_t = sqrt(max(Float4(1.0f) - Float4(1.0f - cos_theta * cos_theta) / (eta_ * eta_), Float4(0.0f)));
  return transmit * exp(Float4(-thickness_) / max(mu_t, Float4(1e-20f)));
}

double coat_internal_reflectance(double eta, double thickness) {
  // 2∫ g(x) dx over [a, b] (composite Simpson, `intervals` even).
  const auto simpson = [](const auto& g, double a, double b, int intervals) {
    return 2.0 * simpson_integral(g, a, b, intervals);
  };
  const auto attenuation = [thickness](double mu) { return mu > 0.0 ? std::exp(-2.0 * thickness / mu) : 0.0; };
  // From inside, the index ratio is 1/η: total reflection below μc = √(1 − 1/η²).
  const double mu_critical = std::sqrt(std::max(0.0, 1.0 - 1.0 / (eta * eta)));
  const double total = simpson([&](double mu) { return attenuation(mu) * mu; }, 0.0, mu_critical, 512);
  const auto partial = [&](double t) {
    const double mu = mu_critical + t * t;
    return fresnel_dielectric(-mu, eta) * attenuation(mu) * mu * 2.0 * t;
  };
  return total + simpson(partial, 0.0, std::sqrt(1.0 - mu_critical), 512);
}

SampledSpectrum CoatedDiffuseBsdf::specular_probability(SampledSpectrum coat_reflectance) const {
  return coat_reflectance / (coat_reflectance + (Float4(1.0f) - coat_reflectance) * Float4(mean_albedo_));
}

SampledSpectrum CoatedDiffuseBsdf::eval(Vec3 wo, Vec3 wi) const {
  const float side = side_of(wo);
  wo = flip_z(wo, side);
  wi = flip_z(wi, side);
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return Float4(0.0f);
  return diffuse_scale_ * crossing(wo.z) * crossing(wi.z);
}

SampledSpectrum CoatedDiffuseBsdf::pdf(Vec3 wo, Vec3 wi) const {
  const float side = side_of(wo);
  wo = flip_z(wo, side);
  wi = flip_z(wi, side);
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return Float4(0.0f);
  const Float4 p_specular = specular_probability(fresnel_dielectric(Float4(wo.z), eta_));
  return (Float4(1.0f) - p_specular) * Float4(cosine_hemisphere_pdf(wi.z));
}

std::optional<BsdfSample> CoatedDiffuseBsdf::sample(Vec3 wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  const float side = side_of(wo);
  const Vec3 wo_up = flip_z(wo, side);
  const Float4 coat_reflectance = fresnel_dielectric(Float4(wo_up.z), eta_);
  const Float4 p_specular = specular_probability(coat_reflectance);
  if (u_lobe < p_specular[0]) {
    // The coat's mirror: f·cos θi = F per lane, chosen with probability p.
    const Vec3 wi{-wo.x, -wo.y, wo.z};
    return BsdfSample{wi, coat_reflectance / Float4(wo_up.z), p_specular, true};
  }
  const Vec3 wi_up = sample_cosine_hemisphere(u);
  if (wi_up.z == 0.0f) return std::nullopt;
  const Vec3 wi = flip_z(wi_up, side);
  return BsdfSample{wi, eval(wo, wi), pdf(wo, wi)};
}

}  // namespace rimu
