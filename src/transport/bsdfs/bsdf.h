// Any of Rimu's BSDFs, held by value: what a material produces at a hit and the integrator consumes.
#pragma once

#include <optional>
#include <variant>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"
#include "transport/bsdfs/coated_diffuse_bsdf.h"
#include "transport/bsdfs/conductor_bsdf.h"
#include "transport/bsdfs/dielectric_bsdf.h"
#include "transport/bsdfs/diffuse_bsdf.h"
#include "transport/bsdfs/diffuse_transmission_bsdf.h"
#include "transport/bsdfs/hair_bsdf.h"
#include "transport/bsdfs/layered_bsdf.h"
#include "transport/bsdfs/measured_bsdf.h"
#include "transport/bsdfs/thin_dielectric_bsdf.h"

namespace rimu {

/// One BSDF of any kind, without heap allocation (a std::variant: its size is that of the largest BSDF).
/// The contract of every method is the one stated in bsdf_sample.h: local shading frame, wo and wi pointing
/// away from the surface, eval() without the cosine, pdf() per lane as if that lane were the hero, sample()
/// driven by the hero wavelength.
///
/// Sides: opaque BSDFs (flags().has_transmission == false) are two-sided, and give the same result as if the
/// frame were flipped so that wo.z > 0; the integrator may flip the shading frame for them. Transmissive BSDFs
/// (the dielectrics) use the sign of wo.z to know whether the path is inside, so the integrator must pass the
/// frame of the geometric outside (the normal pointing out of the object).
class Bsdf {
 public:
  using Variant = std::variant<DiffuseBsdf, ConductorBsdf, DielectricBsdf, CoatedDiffuseBsdf, ThinDielectricBsdf,
                               DiffuseTransmissionBsdf, LayeredBsdf, HairBsdf, MeasuredBsdf>;

  template <typename T>
  Bsdf(T bsdf) : bsdf_(std::move(bsdf)) {}  // NOLINT(google-explicit-constructor): any BSDF is a Bsdf

  /// f(wo, wi) per lane, without |cos θi|; 0 for delta lobes.
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const {
    return std::visit([&](const auto& b) { return b.eval(wo, wi); }, bsdf_);
  }
  /// Per-lane solid-angle density of sample() producing wi; 0 for delta lobes.
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const {
    return std::visit([&](const auto& b) { return b.pdf(wo, wi); }, bsdf_);
  }
  /// A direction drawn with the hero wavelength: `u_lobe` chooses the lobe, `u` the direction within it.
  /// std::nullopt when no direction can be produced; never a sample with pdf[0] = 0.
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const {
    return std::visit([&](const auto& b) { return b.sample(wo, u_lobe, u); }, bsdf_);
  }
  /// sample(), except that a costly BSDF (evaluation_is_costly) leaves a non-delta sample's density to the caller
  /// (BsdfSample::density_deferred): the layered BSDF's density is a second random walk (pdf()), which only MIS
  /// reads, and a path needs it only where its next segment reaches a light. The same sample and weight as sample().
  std::optional<BsdfSample> sample_deferring_density(Vec3 wo, float u_lobe, Vec2 u) const {
    if (const auto* layered = std::get_if<LayeredBsdf>(&bsdf_)) return layered->sample(wo, u_lobe, u, false);
    return sample(wo, u_lobe, u);
  }
  BsdfFlags flags() const {
    return std::visit([](const auto& b) { return b.flags(); }, bsdf_);
  }

  /// Whether eval() and pdf() cost more than a shadow ray: the layered BSDF runs a random walk in each (≈ 1 µs per
  /// call with a rough coat, docs/benchmarks.md "BSDF cost"), so the volumetric integrator's next-event estimation
  /// tests the light's visibility first and evaluates the BSDF only towards lights it sees. Every other BSDF is a few to ~100 ns, and
  /// a direction where it is 0 (a black diffuse) then saves the shadow ray.
  bool evaluation_is_costly() const { return std::holds_alternative<LayeredBsdf>(bsdf_); }
  const Variant& variant() const { return bsdf_; }

 private:
  Variant bsdf_;
};

}  // namespace rimu
