#include "transport/thin_dielectric_bsdf.h"

#include <cmath>

#include "transport/fresnel.h"

namespace rimu {

SampledSpectrum ThinDielectricBsdf::reflectance(float abs_cos_theta) const {
  const SampledSpectrum r0 = fresnel_dielectric(Float4(abs_cos_theta), eta_);
  const SampledSpectrum t0 = Float4(1.0f) - r0;
  // Geometric series of the bounces inside the sheet: R₀ + T₀² R₀ Σ (R₀²)ⁿ. At grazing incidence R₀ = 1 and the
  // series' denominator vanishes; its limit is 1 (everything reflected), which the select keeps finite.
  const SampledSpectrum denominator = Float4(1.0f) - r0 * r0;
  const SampledSpectrum total = r0 + t0 * t0 * r0 / select(denominator > Float4(0.0f), denominator, Float4(1.0f));
  return select(r0 < Float4(1.0f), total, Float4(1.0f));
}

std::optional<BsdfSample> ThinDielectricBsdf::sample(Vec3 wo, float u_lobe, Vec2 /*u*/) const {
  if (wo.z == 0.0f) return std::nullopt;
  const float abs_cos = std::fabs(wo.z);
  const SampledSpectrum r = reflectance(abs_cos);
  if (u_lobe < r[0]) {
    // Mirror: f = R δ / |cos θi|, chosen with probability R: the hero's weight f·|cos|/pdf is 1.
    return BsdfSample{{-wo.x, -wo.y, wo.z}, r / Float4(abs_cos), r, true};
  }
  const SampledSpectrum t = Float4(1.0f) - r;
  return BsdfSample{-wo, t / Float4(abs_cos), t, true};
}

}  // namespace rimu
