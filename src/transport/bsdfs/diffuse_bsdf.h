// The Lambertian BSDF: light is scattered equally in all directions of the hemisphere it came from.
#pragma once

#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"

namespace rimu {

/// f = ρ/π on the side of wo; its directional albedo ∫ f cos θi dωi is ρ for every wo.
/// Two-sided: wo below the surface (wo.z < 0) scatters into the lower hemisphere, as if the frame were flipped.
class DiffuseBsdf {
 public:
  /// `albedo` ρ per lane, in [0, 1] for energy conservation (not enforced: the material clamps).
  explicit DiffuseBsdf(SampledSpectrum albedo) : albedo_(albedo) {}

  /// ρ/π per lane when wo and wi are strictly on the same side, else 0.
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  /// The cosine density |cos θi|/π, equal in all lanes (sampling does not depend on λ).
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// A cosine-distributed wi on wo's side; weight f·cos/pdf = ρ. std::nullopt if wo.z = 0 or wi lands on the
  /// horizon. `u_lobe` is unused (one lobe).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  BsdfFlags flags() const { return {false, true, false}; }

  SampledSpectrum albedo() const { return albedo_; }

 private:
  SampledSpectrum albedo_;
};

}  // namespace rimu
