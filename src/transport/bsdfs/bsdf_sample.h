// The result of sampling a BSDF, and the contract every BSDF follows.
//
// Conventions (all BSDFs):
// - Directions are in the local shading frame (normal = +z), unit length, and both point AWAY from the surface:
//   wo towards the viewer (the previous path vertex), wi towards the next vertex / the light.
// - eval(wo, wi) returns f(wo, wi) per lane: the BSDF itself, NOT multiplied by |cos θi|. Delta (specular)
//   lobes contribute 0 to eval() and pdf(): they can only be sampled.
// - pdf(wo, wi) is the solid-angle density of sample() producing wi, per lane: lane j holds the density that
//   sample() would have had if lane j's wavelength had been the hero. Spectral MIS needs all four.
// - sample() draws wi using the HERO wavelength (lane 0) only. It returns std::nullopt when no direction can be
//   produced (e.g. wo below a one-sided surface); it never returns a zero-pdf sample.
// - Both sides: a BSDF is defined for wo.z < 0 too (two-sided materials flip the frame; dielectrics use the
//   sign of wo.z to know whether the ray is inside).
#pragma once

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/geometry/vector.h"

namespace rimu {

struct BsdfSample {
  Vec3 wi;              ///< sampled direction, local frame
  SampledSpectrum f;    ///< f(wo, wi) per lane; for a delta lobe, the Dirac coefficient (pbrt-v4 convention)
  SampledSpectrum pdf;  ///< per-lane density (solid angle; for a delta lobe, the lobe's discrete probability)
  bool is_delta = false;       ///< specular: eval()/pdf() cannot reproduce this sample; MIS with lights is impossible
  /// True when wi depends on the wavelength (dispersive refraction): the other lanes could not have produced
  /// this direction, so their pdf lanes are 0 and spectral MIS gives their contributions zero weight.
  bool wavelength_dependent_direction = false;
  /// A transmission's index ratio η' = n(wi's side)/n(wo's side), hero lane; 1 for a reflection or where no
  /// radiance scaling applies. f carries 1/η'² (radiance scaling), which is no loss of energy: the path regains it
  /// on leaving the medium, so Russian roulette divides it out of the throughput (pbrt-v4's etaScale).
  float eta = 1.0f;
  /// Set only by Bsdf::sample_deferring_density, on a non-delta sample of a BSDF whose pdf() is costly: the density
  /// was not computed. `pdf` then holds 1 in every lane and `f` the weight f·|cos θi|/pdf divided by |cos θi|, so
  /// that f·|cos θi|/pdf is still the weight and the lanes' density ratios are 1 (such a BSDF's density is equal
  /// in every lane); the density itself is pdf(wo, wi), for the integrator to evaluate where MIS needs it.
  bool density_deferred = false;

  /// The weight f·|cos θi| / pdf of the hero lane — what a single-wavelength estimator multiplies by.
  SampledSpectrum hero_weight() const { return f * Float4(std::fabs(wi.z) / pdf[0]); }
};

}  // namespace rimu
