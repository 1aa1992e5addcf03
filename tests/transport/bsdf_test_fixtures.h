// BSDFs that the reciprocity and energy tests both run over, built in one place so the two check the same set.
#pragma once

#include <array>
#include <string_view>

#include "spectral/library/optical_constants.h"
#include "test_support.h"
#include "transport/bsdfs/bsdf.h"

namespace rimu::test {

/// Four wavelengths spread over the visible, 450 nm the hero, with unit pdf (only the spectral values matter here).
inline SampledWavelengths four_visible_wavelengths() {
  return SampledWavelengths(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f));
}

/// BK7's refractive index at `lambda`: a real, mildly dispersive glass.
inline Float4 bk7_eta(const SampledWavelengths& lambda) { return dielectric_ior(library(), "bk7")->sample(lambda); }

/// One BSDF of each kind, rough and with a different value in every lane: a Lambertian, an anisotropic rough
/// conductor of `metal` (a conductor_ior() name), a rough dielectric and a coated diffuse, both of index `eta`.
inline std::array<Bsdf, 4> one_bsdf_of_each_kind(std::string_view metal, const SampledWavelengths& lambda, Float4 eta) {
  const ComplexIorSpectra conductor = conductor_ior(library(), metal);
  return {
      DiffuseBsdf(Float4(0.9f, 0.5f, 0.2f, 0.1f)),
      ConductorBsdf(conductor.n->sample(lambda), conductor.k->sample(lambda), TrowbridgeReitz(0.3f, 0.1f)),
      DielectricBsdf(eta, TrowbridgeReitz(0.3f, 0.3f)),
      CoatedDiffuseBsdf(Float4(0.9f, 0.5f, 0.2f, 0.1f), eta, Float4(0.09f)),
  };
}

}  // namespace rimu::test
