#include "transport/coated_diffuse_bsdf.h"

#include <algorithm>
#include <numbers>

#include "transport/direction_warps.h"
#include "transport/fresnel.h"

namespace rimu {
namespace {

float side_of(Vec3 wo) { return wo.z < 0.0f ? -1.0f : 1.0f; }
Vec3 flip_z(Vec3 w, float side) { return {w.x, w.y, w.z * side}; }

}  // namespace

CoatedDiffuseBsdf::CoatedDiffuseBsdf(SampledSpectrum albedo, SampledSpectrum eta,
                                     SampledSpectrum diffuse_fresnel_external)
    : albedo_(albedo), eta_(eta) {
  const Float4 eta2 = eta * eta;
  // Reciprocity of the interface for diffuse flux: (1 − F̄_int) η² = 1 − F̄_ext.
  const Float4 internal = Float4(1.0f) - (Float4(1.0f) - diffuse_fresnel_external) / eta2;
  diffuse_scale_ = albedo * Float4(std::numbers::inv_pi_v<float>) / (eta2 * (Float4(1.0f) - albedo * internal));
  mean_albedo_ = std::max(0.25f * sum(albedo), 0.05f);
}

SampledSpectrum CoatedDiffuseBsdf::specular_probability(SampledSpectrum coat_reflectance) const {
  return coat_reflectance / (coat_reflectance + (Float4(1.0f) - coat_reflectance) * Float4(mean_albedo_));
}

SampledSpectrum CoatedDiffuseBsdf::eval(Vec3 wo, Vec3 wi) const {
  const float side = side_of(wo);
  wo = flip_z(wo, side);
  wi = flip_z(wi, side);
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return Float4(0.0f);
  const Float4 transmit_o = Float4(1.0f) - fresnel_dielectric(Float4(wo.z), eta_);
  const Float4 transmit_i = Float4(1.0f) - fresnel_dielectric(Float4(wi.z), eta_);
  return diffuse_scale_ * transmit_o * transmit_i;
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
