#include "transport/bsdfs/thin_dielectric_bsdf.h"

#include <cmath>

#include "transport/bsdfs/fresnel.h"

namespace rimu {

ThinDielectricBsdf::ThinDielectricBsdf(SampledSpectrum eta, SampledSpectrum internal_transmittance)
    : eta_(eta), internal_transmittance_(clamp(internal_transmittance, Float4(0.0f), Float4(1.0f))) {}

ThinDielectricBsdf::Lobes ThinDielectricBsdf::lobes(float abs_cos_theta) const {
  const SampledSpectrum r0 = fresnel_dielectric(Float4(abs_cos_theta), eta_);
  const SampledSpectrum t0 = Float4(1.0f) - r0;
  const SampledSpectrum one(1.0f);
  if (!internal_transmittance_) {
    // Geometric series of the bounces inside the sheet: R₀ + T₀² R₀ Σ (R₀²)ⁿ. At grazing incidence R₀ = 1 and the
    // series' denominator vanishes; its limit is 1 (everything reflected), which the select keeps finite.
    const SampledSpectrum denominator = one - r0 * r0;
    const SampledSpectrum total = r0 + t0 * t0 * r0 / select(denominator > Float4(0.0f), denominator, one);
    const SampledSpectrum r = select(r0 < one, total, one);
    return {r, one - r};
  }
  // τ at this angle: τₙ^(1/cos θt), cos θt = √(1 − sin²θ/η²) inside the glass (η ≥ 1 keeps it real; an η < 1
  // sheet has total internal reflection, where R₀ = 1 and τ no longer matters).
  const float sin2 = std::fmax(0.0f, 1.0f - abs_cos_theta * abs_cos_theta);
  float tau_lanes[kLaneCount];
  for (int k = 0; k < kLaneCount; ++k) {
    const float cos_t2 = 1.0f - sin2 / (eta_[k] * eta_[k]);
    const float tau_n = (*internal_transmittance_)[k];
    tau_lanes[k] = cos_t2 > 0.0f && tau_n > 0.0f ? std::pow(tau_n, 1.0f / std::sqrt(cos_t2)) : 0.0f;
  }
  const SampledSpectrum tau(tau_lanes[0], tau_lanes[1], tau_lanes[2], tau_lanes[3]);
  const SampledSpectrum rt = r0 * tau;
  const SampledSpectrum denominator = one - rt * rt;
  const SampledSpectrum safe = select(denominator > Float4(0.0f), denominator, one);
  const SampledSpectrum r = select(r0 < one, r0 + t0 * t0 * r0 * tau * tau / safe, one);
  const SampledSpectrum t = select(r0 < one, t0 * t0 * tau / safe, Float4(0.0f));
  return {r, t};
}

SampledSpectrum ThinDielectricBsdf::reflectance(float abs_cos_theta) const { return lobes(abs_cos_theta).r; }

ThinDielectricBsdf::StraightThrough ThinDielectricBsdf::straight_through(float abs_cos_theta) const {
  const Lobes l = lobes(abs_cos_theta);
  if (!internal_transmittance_) return {l.t, l.t};
  const SampledSpectrum total = l.r + l.t;
  return {l.t, select(total > Float4(0.0f), l.t / total, Float4(0.0f))};
}

std::optional<BsdfSample> ThinDielectricBsdf::sample(Vec3 wo, float u_lobe, Vec2 /*u*/) const {
  if (wo.z == 0.0f) return std::nullopt;
  const float abs_cos = std::fabs(wo.z);
  const Lobes l = lobes(abs_cos);
  if (!internal_transmittance_) {
    if (u_lobe < l.r[0]) {
      // Mirror: f = R δ / |cos θi|, chosen with probability R: the hero's weight f·|cos|/pdf is 1.
      return BsdfSample{{-wo.x, -wo.y, wo.z}, l.r / Float4(abs_cos), l.r, true};
    }
    return BsdfSample{-wo, l.t / Float4(abs_cos), l.t, true};
  }
  // Absorbing: choose in proportion to R and T (the hero's weight is then R + T, what the sheet does not absorb).
  const SampledSpectrum total = l.r + l.t;
  if (!(total[0] > 0.0f)) return std::nullopt;
  const SampledSpectrum inverse_total = select(total > Float4(0.0f), Float4(1.0f) / total, Float4(0.0f));
  if (u_lobe * total[0] < l.r[0])
    return BsdfSample{{-wo.x, -wo.y, wo.z}, l.r / Float4(abs_cos), l.r * inverse_total, true};
  return BsdfSample{-wo, l.t / Float4(abs_cos), l.t * inverse_total, true};
}

}  // namespace rimu
