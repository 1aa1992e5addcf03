// Fresnel reflectance of smooth interfaces: dielectric (real index) and conductor (complex index), unpolarised.
#pragma once

#include "spectral/wavelengths/sampled_wavelengths.h"

namespace rimu {

/// Unpolarised reflectance of a dielectric interface, F = (r_s² + r_p²)/2, per lane, from the Fresnel equations
/// (Born & Wolf, Principles of Optics, §1.5.2, Eq. 21):
///     r_s = (cos θi − η cos θt)/(cos θi + η cos θt),  r_p = (η cos θi − cos θt)/(η cos θi + cos θt),
/// with η = n_t/n_i and Snell's law sin θt = sin θi / η.
/// `cos_theta_i` is signed against the interface normal, which points to the outside: positive = incident from
/// the outside, negative = from the inside. `eta` = n_inside / n_outside (> 0).
/// Total internal reflection (sin θt ≥ 1) returns exactly 1; grazing incidence (cos θi = 0) returns 1, no NaN.
SampledSpectrum fresnel_dielectric(SampledSpectrum cos_theta_i, SampledSpectrum eta);
/// The two polarisations' reflectances, r_s² and r_p², per lane (fresnel_dielectric is their mean). For what
/// averages after combining reflections, like a thin sheet's inter-reflection series, which must be summed per
/// polarisation: unpolarised light is half s and half p, and each keeps its polarisation at a smooth interface.
/// Total internal reflection: both 1.
struct PolarisedReflectance {
  SampledSpectrum s, p;
};
PolarisedReflectance fresnel_dielectric_polarised(SampledSpectrum cos_theta_i, SampledSpectrum eta);
/// The same for one wavelength, in float (per-lane geometry, e.g. rough refraction) and double (setup-time
/// integrals and tests).
float fresnel_dielectric(float cos_theta_i, float eta);
double fresnel_dielectric(double cos_theta_i, double eta);

/// Unpolarised reflectance of a conductor with complex relative index η = n + ik, per lane: the same Fresnel
/// equations with complex η and the principal root cos θt = √(1 − sin²θi / η²) (Born & Wolf §14.2).
/// At normal incidence this is ((n−1)² + k²)/((n+1)² + k²). `cos_theta_i` in [0, 1] (clamped); grazing gives 1.
SampledSpectrum fresnel_conductor(SampledSpectrum cos_theta_i, SampledSpectrum n, SampledSpectrum k);

/// Hemispherical reflectance of a smooth dielectric interface under uniform diffuse (cosine-weighted) light from
/// the outside: F̄_ext(η) = 2 ∫₀¹ F(μ, η) μ dμ, by composite Simpson quadrature (for η < 1, split at the critical
/// angle with a substitution that removes F's square-root kink there). Error < 1e-7; setup-time cost (about 500
/// Fresnel evaluations).
/// The inside's value follows from reciprocity: 1 − F̄_int = (1 − F̄_ext)/η² (e.g. Judd 1942).
double fresnel_diffuse_reflectance(double eta);

}  // namespace rimu
