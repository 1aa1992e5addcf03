// A Lambertian reflector and transmitter (paper, a lampshade, a thin leaf): light leaves both faces uniformly.
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"

namespace rimu {

/// f = R/π on wo's side and T/π on the other (pbrt-v4's DiffuseTransmissionBxDF); its directional albedo is
/// R + T for every wo, so R + T ≤ 1 per lane conserves energy (the material ensures it). Symmetric in the side
/// of wo, and reciprocal.
///
/// Lobe choice: sample() reflects with probability P = R/(R + T) of the hero lane and transmits otherwise, each
/// cosine-distributed; lane k's pdf uses its own P_k (0 where R_k + T_k = 0: that lane could sample nothing).
/// The hero's weight f·|cos|/pdf is R + T for every sample.
class DiffuseTransmissionBsdf {
 public:
  /// `reflectance` R and `transmittance` T per lane, ≥ 0 with R + T ≤ 1 (not enforced here).
  DiffuseTransmissionBsdf(SampledSpectrum reflectance, SampledSpectrum transmittance)
      : reflectance_(reflectance), transmittance_(transmittance) {}

  /// R/π per lane if wo and wi are strictly on the same side, T/π if strictly on opposite sides, else 0.
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  /// P_k |cos θi|/π on wo's side, (1 − P_k) |cos θi|/π on the other.
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// Reflect if u_lobe < P(hero), else transmit; `u` draws the cosine-distributed direction. std::nullopt if
  /// wo.z = 0, R + T = 0 in the hero lane, or wi lands on the horizon.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const { return {false, true, true}; }

  SampledSpectrum reflectance() const { return reflectance_; }
  SampledSpectrum transmittance() const { return transmittance_; }

 private:
  /// P_k = R_k / (R_k + T_k), 0 where R_k + T_k = 0.
  SampledSpectrum reflect_probability() const;

  SampledSpectrum reflectance_;
  SampledSpectrum transmittance_;
};

}  // namespace rimu
