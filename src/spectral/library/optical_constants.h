// Optical constants as spectra: the refractive index of glasses and water (Sellmeier), and the complex index
// n + ik of metals (measured tables).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/spectra/spectrum.h"

namespace rimu {

class SpectralLibrary;

/// One Sellmeier term B·λ²/(λ² − C), λ in µm, C in µm².
struct SellmeierTerm {
  double b = 0;
  double c_um2 = 0;
};

/// The real refractive index n(λ) of a transparent material from the Sellmeier dispersion formula
///     n² − 1 = Σᵢ Bᵢ λ² / (λ² − Cᵢ),   λ in µm, Cᵢ in µm²
/// (SCHOTT optical glass catalogue, "Sellmeier dispersion formula"; Daimon & Masumura 2007, Eq. 1, for water).
/// Up to four terms, so that sample() is branch-free per lane in the per-sample loop.
class SellmeierSpectrum final : public Spectrum {
 public:
  static constexpr int kMaxTerms = 4;
  /// Throws InputError if there are no terms or more than kMaxTerms, or if a pole Cᵢ lies inside 360-830 nm.
  SellmeierSpectrum(std::vector<SellmeierTerm> terms, std::string name);

  /// n at `lambda_nm` (double precision; for setup and tests).
  double value(double lambda_nm) const override;
  /// n at the four sampled wavelengths (float lanes).
  SampledSpectrum sample(const SampledWavelengths& lambda) const override;
  double max_value() const override { return max_value_; }
  std::string describe() const override { return name_; }

 private:
  std::array<SellmeierTerm, kMaxTerms> terms_{};  // unused terms have B = 0
  std::string name_;
  double max_value_ = 0;
};

/// The complex refractive index n + ik of a conductor, both parts as spectra (relative to vacuum).
struct ComplexIorSpectra {
  SpectrumPtr n;  ///< real part (phase index)
  SpectrumPtr k;  ///< imaginary part (extinction coefficient), ≥ 0
};

/// The names dielectric_ior() knows: "bk7", "sf11", "fused-silica", "water" (Sellmeier), and pbrt-v4's glass
/// tables "pbrt-bk7", "pbrt-baf10", "pbrt-fk51a", "pbrt-lasf9", "pbrt-sf5", "pbrt-sf10", "pbrt-sf11".
std::vector<std::string> dielectric_names();
/// The refractive index of a named dielectric (a SellmeierSpectrum, or a table for pbrt's), from data/spectra/materials.
/// Throws InputError naming the known materials if `name` is not one of them.
SpectrumPtr dielectric_ior(SpectralLibrary& library, std::string_view name);

/// The names conductor_ior() knows: "gold", "silver", "copper", "aluminium" (published measurements), and
/// pbrt-v4's tables "pbrt-au", "pbrt-ag", "pbrt-cu", "pbrt-al", "pbrt-cuzn", "pbrt-mgo", "pbrt-tio2".
std::vector<std::string> conductor_names();
/// The measured n, k of a named metal, linearly interpolated (clamped beyond the table's ends).
/// Throws InputError naming the known metals if `name` is not one of them.
ComplexIorSpectra conductor_ior(SpectralLibrary& library, std::string_view name);

}  // namespace rimu
