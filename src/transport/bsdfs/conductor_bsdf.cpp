#include "transport/bsdfs/conductor_bsdf.h"

#include <cmath>

#include "transport/bsdfs/fresnel.h"
#include "transport/geometry/frame.h"

namespace rimu {
SampledSpectrum ConductorBsdf::fresnel(float cos_theta) const { return fresnel_conductor(Float4(cos_theta), n_, k_); }

SampledSpectrum ConductorBsdf::eval(Vec3 wo, Vec3 wi) const {
  if (distribution_.effectively_smooth()) return Float4(0.0f);
  const float side = side_of(wo);
  wo = flip_z(wo, side);
  wi = flip_z(wi, side);
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return Float4(0.0f);
  const Vec3 h = normalize(wo + wi);
  const float scale = distribution_.d(h) * distribution_.g2(wo, wi) / (4.0f * wo.z * wi.z);
  return fresnel(dot(wo, h)) * Float4(scale);
}

SampledSpectrum ConductorBsdf::pdf(Vec3 wo, Vec3 wi) const {
  if (distribution_.effectively_smooth()) return Float4(0.0f);
  const float side = side_of(wo);
  wo = flip_z(wo, side);
  wi = flip_z(wi, side);
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return Float4(0.0f);
  const Vec3 h = normalize(wo + wi);
  const float wo_dot_h = dot(wo, h);
  if (!(wo_dot_h > 0.0f)) return Float4(0.0f);
  return Float4(distribution_.visible_d(wo, h) / (4.0f * wo_dot_h));
}

std::optional<BsdfSample> ConductorBsdf::sample(Vec3 wo, float /*u_lobe*/, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  const float side = side_of(wo);
  wo = flip_z(wo, side);

  if (distribution_.effectively_smooth()) {
    // Delta mirror: f = F δ(wi − mirror(wo)) / cos θi, so the weight f·cos/pdf is F.
    const Vec3 wi{-wo.x, -wo.y, wo.z};
    return BsdfSample{flip_z(wi, side), fresnel(wo.z) / Float4(wi.z), Float4(1.0f), true};
  }

  const Vec3 h = distribution_.sample_visible(wo, u);
  const Vec3 wi = reflect(wo, h);
  if (!(wi.z > 0.0f)) return std::nullopt;  // reflected below the horizon: this sample is lost (single scattering)
  const float wo_dot_h = dot(wo, h);
  // D and Λ(wo) once for both: D_wo(h) = G1(wo) (wo·h) D(h) / cos θo (TrowbridgeReitz::visible_d; h faces wo).
  const float d = distribution_.d(h), lambda_o = distribution_.lambda(wo);
  const float pdf = d / ((1.0f + lambda_o) * 4.0f * wo.z);
  if (!(wo_dot_h > 0.0f) || !(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;
  const float scale = d / ((1.0f + lambda_o + distribution_.lambda(wi)) * 4.0f * wo.z * wi.z);
  return BsdfSample{flip_z(wi, side), fresnel(wo_dot_h) * Float4(scale), Float4(pdf)};
}

}  // namespace rimu
