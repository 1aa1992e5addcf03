// The Henyey–Greenstein phase function: the scattering lobe of a medium, one asymmetry parameter g.
#pragma once

#include "transport/geometry/vector.h"

namespace rimu {

/// One sampled scattering direction. For HG the sampling is exact, so the weight phase/pdf is 1 and only the
/// density (needed for MIS against light sampling) is returned.
struct PhaseSample {
  Vec3 wi;                  ///< unit direction towards the next vertex
  float pdf_solid_angle = 0;  ///< = phase value: sampling is exact
};

/// p(cos θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}), θ the angle between the propagation direction before
/// and after scattering (Henyey & Greenstein 1941, ApJ 93, Eq. 3). Normalised over the sphere: ∫ p dω = 1, and
/// g = ⟨cos θ⟩ (g > 0 forward, g < 0 backward, 0 isotropic). Wavelength-independent in Rimu: every lane has the
/// same phase function, so phase sampling never changes the spectral-MIS ratios R_k.
///
/// Directions follow the BSDF convention (bsdf_sample.h): wo points back towards the previous vertex, wi towards
/// the next one, both away from the scattering point, so cos θ = −wo·wi.
class HenyeyGreenstein {
 public:
  /// |g| < 1 (asserted by the loader; values are clamped to ±0.99 to keep the density finite).
  explicit HenyeyGreenstein(float g);

  /// The phase function value (= the density of sample()), per steradian.
  float eval(Vec3 wo, Vec3 wi) const;
  /// A direction drawn exactly from the phase function by inverting its CDF in cos θ (see the .cpp).
  PhaseSample sample(Vec3 wo, Vec2 u) const;
  float g() const { return g_; }

 private:
  float g_;
};

/// The HG density as a function of cos θ (between propagation directions), per steradian.
float henyey_greenstein(float cos_theta, float g);

}  // namespace rimu
