// An analytic BRDF written in the measured form (MeasuredBrdf): a rough conductor's tables as an RGL tensor file
// would hold them. Used to check MeasuredBsdf against the analytic ConductorBsdf it tabulates, and to give Rimu and
// pbrt-v4 the same measured file to render (the RGL database's own files are not public in a form this project can
// fetch).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "spectral/library/optical_constants.h"
#include "transport/bsdfs/microfacet.h"
#include "transport/bsdfs/tensor_file.h"

namespace rimu {

struct MicrofacetTabulation {
  TrowbridgeReitz distribution{0.3f, 0.3f};  ///< isotropic: alpha_x is used
  std::vector<float> wavelengths_nm;         ///< increasing
  std::vector<float> n, k;                   ///< the conductor's index at each wavelength
  int theta_i_count = 12;                    ///< incident elevations, evenly spaced in u_θ up to `max_theta_i`
  float max_theta_i = 1.48f;                 ///< radians (85°)
  int ndf_size = 64;                         ///< θ samples of ndf and sigma (φ: 2, isotropic)
  int vndf_size = 48;                        ///< each side of the visible-normal and spectral grids

  /// A conductor of index `ior` under GGX of width `alpha` (isotropic), its n and k read at first_nm,
  /// first_nm + step_nm, … up to last_nm; the other fields at their defaults.
  static MicrofacetTabulation conductor(const ComplexIorSpectra& ior, float alpha, float first_nm = 360.0f,
                                        float last_nm = 830.0f, float step_nm = 10.0f);
};

/// The fields of an isotropic tensor file (theta_i, phi_i = [0], wavelengths, ndf, sigma, vndf, luminance, spectra,
/// description, jacobian) whose MeasuredBsdf approximates ConductorBsdf with the same distribution and n, k (Walter
/// et al.'s GGX with the height-correlated G2): D tabulated directly, σ(ωo) = cos θo (1 + Λ(ωo)), the visible-normal
/// density D⟨ωo, ωm⟩/σ in the square's coordinates, and the spectral factor S = F(ωo·ωm) G2(ωo, ωi)/G1(ωo) at the
/// points the visible-normal warp maps the spectral grid to, so that S D/(4σ cos θi) = D G2 F/(4 cos θo cos θi).
/// The luminance table is S averaged over the wavelengths.
std::map<std::string, TensorFile::Field> tabulate_microfacet_brdf(const MicrofacetTabulation& tabulation);

}  // namespace rimu
