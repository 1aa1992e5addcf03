// A medium with the same coefficients everywhere: σ_a(λ), σ_s(λ) as spectra, and an HG phase function.
#pragma once

#include "spectral/spectra/spectrum.h"
#include "transport/media/henyey_greenstein.h"

namespace rimu {

/// Absorption and scattering coefficients at the four wavelengths of a path, per metre.
struct MediumCoefficients {
  SampledSpectrum sigma_a_per_m;
  SampledSpectrum sigma_s_per_m;
  SampledSpectrum sigma_t_per_m() const { return sigma_a_per_m + sigma_s_per_m; }
};

/// σ_a(λ) and σ_s(λ) in 1/m (any Spectrum: tabulated, upsampled, constant) and a wavelength-independent HG g.
class HomogeneousMedium {
 public:
  /// Both spectra must be ≥ 0 and finite over 360-830 nm (the loader checks; asserted here).
  HomogeneousMedium(SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m, float g);

  /// The coefficients at the path's wavelengths (two spectrum lookups; once per path segment).
  MediumCoefficients coefficients(const SampledWavelengths& lambda) const {
    return {max(sigma_a_->sample(lambda), Float4(0.0f)), max(sigma_s_->sample(lambda), Float4(0.0f))};
  }
  const HenyeyGreenstein& phase() const { return phase_; }
  const SpectrumPtr& sigma_a() const { return sigma_a_; }
  const SpectrumPtr& sigma_s() const { return sigma_s_; }

 private:
  SpectrumPtr sigma_a_, sigma_s_;
  HenyeyGreenstein phase_;
};

/// Single-scattering albedo α from the multiple-scattering ("surface") albedo A of a semi-infinite medium with
/// an index-matched boundary: α = 1 − exp(−11.43 A + 15.38 A² − 13.91 A³) (Chiang, Kutz, Burley 2016,
/// "Practical and Controllable Subsurface Scattering for Production Path Tracing", SIGGRAPH Talks, Eq. 2; their
/// fit to brute-force path-traced slabs, for isotropic scattering).
double chiang2016_single_scattering_albedo(double multiple_scattering_albedo);

/// Chiang et al. 2016 at one wavelength (or one RGB channel): σ_t = 1/d with the mean free path d in metres
/// (clamped to ≥ 1e-9 m: a zero mean free path would be an infinite coefficient), σ_s = α(A)·σ_t, σ_a = σ_t − σ_s.
struct Chiang2016Coefficients {
  double sigma_a_per_m, sigma_s_per_m;
};
Chiang2016Coefficients chiang2016_coefficients(double surface_albedo, double mean_free_path_m);

/// The artist parameterisation of Chiang et al. 2016: a surface albedo A(λ) ∈ [0, 1] and a mean free path d(λ)
/// in metres give σ_t = 1/d, σ_s = α(A)·σ_t, σ_a = σ_t − σ_s. Tabulated at 1 nm over 360-830 nm at load time.
HomogeneousMedium chiang2016_medium(const Spectrum& surface_albedo, const Spectrum& mean_free_path_m, float g);

}  // namespace rimu
