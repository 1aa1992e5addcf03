#include "transport/bsdfs/thin_dielectric_bsdf.h"

#include <cmath>

#include "transport/bsdfs/fresnel.h"

namespace rimu {

ThinDielectricBsdf::ThinDielectricBsdf(SampledSpectrum eta, SampledSpectrum internal_transmittance)
    : eta_(eta), internal_transmittance_(clamp(internal_transmittance, Float4(0.0f), Float4(1.0f))) {}

namespace {

// One polarisation's series: R = R₀ + T₀² R₀ τ² / (1 − R₀² τ²), T = T₀² τ / (1 − R₀² τ²) (τ = 1: T = 1 − R). At
// grazing incidence R₀ = 1 and the denominator vanishes for a clear sheet; the limit is R = 1, T = 0, which the
// selects keep finite.
struct SeriesSums {
  SampledSpectrum r, t;
};
SeriesSums sheet_series(SampledSpectrum r0, SampledSpectrum tau) {
  const SampledSpectrum one(1.0f);
  const SampledSpectrum t0 = one - r0;
  const SampledSpectrum rt = r0 * tau;
  const SampledSpectrum denominator = one - rt * rt;
  const SampledSpectrum safe = select(denominator > Float4(0.0f), denominator, one);
  const SampledSpectrum r = select(r0 < one, r0 + t0 * t0 * r0 * tau * tau / safe, one);
  const SampledSpectrum t = select(r0 < one, t0 * t0 * tau / safe, Float4(0.0f));
  return {r, t};
}

}  // namespace

ThinDielectricBsdf::Lobes ThinDielectricBsdf::lobes(float abs_cos_theta) const {
  // The series is summed per polarisation and then averaged: unpolarised light is half s and half p, each keeps its
  // polarisation through the sheet, and the series is not linear in R₀, so averaging R₀ first (pbrt-v4's
  // ThinDielectricBxDF) overstates R at oblique incidence: a clear η = 1.5 pane then transmits 0.836 at 60° instead
  // of 0.848, 0.708 at 70° instead of 0.729.
  const PolarisedReflectance r0 = fresnel_dielectric_polarised(Float4(abs_cos_theta), eta_);
  SampledSpectrum tau(1.0f);
  if (internal_transmittance_) {
    // τ at this angle: τₙ^(1/cos θt), cos θt = √(1 − sin²θ/η²) inside the glass (η ≥ 1 keeps it real; an η < 1
    // sheet has total internal reflection, where R₀ = 1 and τ no longer matters).
    const float sin2 = std::fmax(0.0f, 1.0f - abs_cos_theta * abs_cos_theta);
    float tau_lanes[kLaneCount];
    for (int k = 0; k < kLaneCount; ++k) {
      const float cos_t2 = 1.0f - sin2 / (eta_[k] * eta_[k]);
      const float tau_n = (*internal_transmittance_)[k];
      tau_lanes[k] = cos_t2 > 0.0f && tau_n > 0.0f ? std::pow(tau_n, 1.0f / std::sqrt(cos_t2)) : 0.0f;
    }
    tau = SampledSpectrum(tau_lanes[0], tau_lanes[1], tau_lanes[2], tau_lanes[3]);
  }
  const SeriesSums s = sheet_series(r0.s, tau), p = sheet_series(r0.p, tau);
  const SampledSpectrum half(0.5f);
  const SampledSpectrum r = half * (s.r + p.r);
  // A clear sheet is lossless: T = 1 − R exactly, as sample() assumes.
  if (!internal_transmittance_) return {r, SampledSpectrum(1.0f) - r};
  return {r, half * (s.t + p.t)};
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
