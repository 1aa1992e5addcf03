#include "transport/bsdfs/diffuse_bsdf.h"

#include <numbers>

#include "transport/sampling/direction_warps.h"
#include "transport/geometry/frame.h"

namespace rimu {

SampledSpectrum DiffuseBsdf::eval(Vec3 wo, Vec3 wi) const {
  if (!same_hemisphere(wo, wi)) return Float4(0.0f);
  return albedo_ * Float4(std::numbers::inv_pi_v<float>);
}

SampledSpectrum DiffuseBsdf::pdf(Vec3 wo, Vec3 wi) const {
  if (!same_hemisphere(wo, wi)) return Float4(0.0f);
  return Float4(cosine_hemisphere_pdf(abs_cos_theta(wi)));
}

std::optional<BsdfSample> DiffuseBsdf::sample(Vec3 wo, float /*u_lobe*/, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  Vec3 wi = sample_cosine_hemisphere(u);
  if (wo.z < 0.0f) wi.z = -wi.z;
  // The disk's boundary lifts to the horizon, where the pdf is 0: the contract forbids returning it.
  if (wi.z == 0.0f) return std::nullopt;
  return BsdfSample{wi, eval(wo, wi), pdf(wo, wi)};
}

}  // namespace rimu
