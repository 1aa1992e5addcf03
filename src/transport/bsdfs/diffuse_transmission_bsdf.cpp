#include "transport/bsdfs/diffuse_transmission_bsdf.h"

#include <numbers>

#include "transport/sampling/direction_warps.h"
#include "transport/geometry/frame.h"

namespace rimu {

SampledSpectrum DiffuseTransmissionBsdf::reflect_probability() const {
  const SampledSpectrum total = reflectance_ + transmittance_;
  return select(total > Float4(0.0f), reflectance_ / select(total > Float4(0.0f), total, Float4(1.0f)), Float4(0.0f));
}

SampledSpectrum DiffuseTransmissionBsdf::eval(Vec3 wo, Vec3 wi) const {
  const float side = wo.z * wi.z;
  if (side == 0.0f) return Float4(0.0f);
  return (side > 0.0f ? reflectance_ : transmittance_) * Float4(std::numbers::inv_pi_v<float>);
}

SampledSpectrum DiffuseTransmissionBsdf::pdf(Vec3 wo, Vec3 wi) const {
  const float side = wo.z * wi.z;
  if (side == 0.0f) return Float4(0.0f);
  const SampledSpectrum p = reflect_probability();
  const SampledSpectrum total = reflectance_ + transmittance_;
  // A lane with R + T = 0 would have returned no sample: its density is 0 on both sides.
  const SampledSpectrum lobe = select(total > Float4(0.0f), side > 0.0f ? p : Float4(1.0f) - p, Float4(0.0f));
  return lobe * Float4(cosine_hemisphere_pdf(abs_cos_theta(wi)));
}

std::optional<BsdfSample> DiffuseTransmissionBsdf::sample(Vec3 wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  if (!(reflectance_[0] + transmittance_[0] > 0.0f)) return std::nullopt;
  Vec3 wi = sample_cosine_hemisphere(u);  // upper hemisphere
  const bool reflect = u_lobe < reflect_probability()[0];
  // Reflection stays on wo's side, transmission crosses to the other.
  if ((wo.z < 0.0f) == reflect) wi.z = -wi.z;
  if (wi.z == 0.0f) return std::nullopt;  // the horizon has pdf 0: the contract forbids returning it
  BsdfSample s{wi, eval(wo, wi), pdf(wo, wi)};
  if (!(s.pdf[0] > 0.0f)) return std::nullopt;  // P(hero) = 0 or 1 and u_lobe chose the empty lobe
  return s;
}

}  // namespace rimu
