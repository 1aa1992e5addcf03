// RGB → spectrum: Meng et al. (2015) smoothest spectra, per colour space, with gamut mapping for reflectances.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>

#include "spectral/error.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/library/spectral_library.h"
#include "spectral/upsampling/upsampled_spectrum.h"
#include "spectral/upsampling/upsampling_basis.h"
#include "spectral/upsampling/upsampling_table.h"

namespace rimu {

/// An upsampled reflectance and what gamut mapping did to reach it.
struct UpsampledReflectance {
  ReflectanceSpectrum spectrum;
  bool gamut_mapped = false;  ///< true if the spectrum's colour is not the input's (chromaticity or brightness moved)
  double delta_e2000 = 0;     ///< CIEDE2000 between input and spectrum under the space's white (reference Y = 1)
};

/// An upsampled emission spectrum and whether its chromaticity had to move (emission has no brightness limit).
struct UpsampledEmission {
  EmissionSpectrum spectrum;
  bool gamut_mapped = false;  ///< true if the input chromaticity lay outside the gamut of non-negative spectra
  double delta_e2000 = 0;     ///< CIEDE2000 of the chromaticity shift, both colours taken at L* = 100
};

/// Turns linear RGB of one colour space into spectra (docs/upsampling.md has the method and its accuracy).
///
/// Setup (the constructor) loads the table for the space's white and builds the knot colorimetry; then every
/// upsample_* call is independent, allocation-free and thread-safe (the object is immutable).
///
/// Both upsample_* functions: RGB → XYZ (the space's matrix, Y(white) = 1) → polar coordinates (θ, ρ) around the
/// white in the knot gamut → bilinear interpolation of the table's Y-normalised spectra → a correction that
/// restores the exact target colour (the smallest change Σ ΔS_i²/S_i, which keeps zeros at zero: ΔS = diag(S)·Aᵀλ,
/// with λ from the 3×3 system A·diag(S)·Aᵀ·λ = residual, repeated while clamping at 0) → scaled to Y.
///
/// Defined behaviour for inputs that have no non-negative spectrum:
/// - RGB (0,0,0) → exactly zero, not "mapped".
/// - Y ≤ 0 or X+Y+Z ≤ 0 (possible with negative components) → zero, gamut_mapped.
/// - a chromaticity outside the usable gamut (negative components or primaries beyond the spectral locus, e.g.
///   ACES AP0, AP1 green) → moved along the straight line towards the white to the gamut edge, Y kept, gamut_mapped.
///   Negative components whose colour is inside the locus need no mapping: the spectrum stays ≥ 0 and reproduces
///   the negative RGB exactly.
/// - NaN or ±Inf in any component → InputError (with `where`).
class RgbUpsampler {
 public:
  /// Loads data/upsampling/smooth_<white>.bin. Throws InputError if the space's white has no table.
  RgbUpsampler(SpectralLibrary& library, const RgbColourSpace& space);

  /// A reflectance in [0,1] whose colour under the space's white is `rgb`, or the nearest one the gamut-mapping
  /// rule allows: chromaticity kept (moved to the gamut edge only if outside it), luminance Y clipped to the
  /// brightness limit Y_max(xy) = Y of the smooth spectrum scaled to peak 1. Cost ~1-2 µs.
  UpsampledReflectance upsample_reflectance(const Rgb& rgb, const SourceLocation& where = {}) const;

  /// The spectrum of upsample_reflectance alone, without its diagnostics (gamut_mapped, ΔE2000 of the round
  /// trip, which cost another colorimetric integral and a CIEDE2000), for callers that discard them. Same
  /// spectrum, bit for bit (tested).
  ReflectanceSpectrum reflectance_spectrum(const Rgb& rgb, const SourceLocation& where = {}) const;

  /// An emission spectrum whose absolute colour (emission_xyz) is `rgb`'s XYZ read in cd/m², up to the
  /// illuminant-vs-rounded-white difference of KnotColorimetry (≤ 1e-4): the white illuminant W times the smooth
  /// spectrum of the input chromaticity, scaled so Y matches. No upper limit; RGB (1,1,1) gives W itself.
  UpsampledEmission upsample_emission(const Rgb& rgb, const SourceLocation& where = {}) const;

  // The fast path (docs/upsampling.md, "Fast path"): the same method with the table's entries as coefficients of
  // UpsamplingBasis, so an upsampled colour costs 0.15-0.3 µs instead of 1-6 µs (the basis is built on the first
  // fast-path call: ~0.1-0.2 s per colour space). Same gamut mapping and brightness
  // limit as upsample_reflectance/upsample_emission; the colour is exact up to float rounding before clamping,
  // and the spectrum differs from the exact path's by the basis truncation (docs/upsampling.md has both errors).
  // For per-texel conversion and anything that needs many colours; colorimetry and the toolkit use the exact path.

  /// Coefficients of the reflectance upsample_reflectance would give (gamut mapping and brightness limit
  /// included). The spectrum is basis().evaluate_clamped(c, λ, 0, 1), rendered by evaluate() (ringing dips below 0
  /// where the exact spectrum is zero); its colour is the target's to ~1e-5. `mapped`: the colour moved — gamut
  /// mapping, the brightness limit, or a spectrum the basis cannot hold in [0, 1] (residual > 1e-4: saturated
  /// purples of the wide spaces, docs/upsampling.md). ~150 ns, plus ~50-90 ns per 95-knot pass for saturated
  /// colours and colours near the brightness limit (1-3 passes).
  BasisCoefficients reflectance_coefficients(const Rgb& rgb, bool* mapped = nullptr, const SourceLocation& where = {}) const;
  /// reflectance_coefficients as knots, clamped to [0, 1]: a ReflectanceSpectrum (4-lane evaluation as the exact
  /// path's, ~3 ns). One 95-knot pass more than reflectance_coefficients.
  ReflectanceSpectrum fast_reflectance_spectrum(const Rgb& rgb, const SourceLocation& where = {}) const;
  /// Coefficients of upsample_emission's smooth factor s times the input luminance Y (cd/m²): the emission is
  /// basis().evaluate_clamped(c, λ, 0, ∞) · W(λ) · emission_scale(). `mapped` as upsample_emission's
  /// gamut_mapped, or the clamped spectrum missing the colour by more than 1e-4 (chromaticities within ~10 % of
  /// the locus in purple-red directions). Cost as reflectance_coefficients.
  BasisCoefficients emission_coefficients(const Rgb& rgb, bool* mapped = nullptr, const SourceLocation& where = {}) const;
  /// emission_coefficients as an EmissionSpectrum (knots clamped at 0).
  EmissionSpectrum fast_emission_spectrum(const Rgb& rgb, const SourceLocation& where = {}) const;
  /// Radiance in W/(m²·sr·nm) per unit of the smooth factor times W: 1 / (K_m Σ W ȳ Δλ).
  double emission_scale() const { return emission_scale_; }
  /// The fast path's basis, built on the first call (~0.1-0.2 s, most of the upsampler's construction: scenes and
  /// tools that use only the exact path never pay it); thread-safe, and one atomic load once built.
  const UpsamplingBasis& basis() const {
    const UpsamplingBasis* built = lazy_basis_->built.load(std::memory_order_acquire);
    return built ? *built : build_basis();
  }

  /// The smooth spectrum of chromaticity `xy` with Y = 1 (xy moved to the gamut edge if outside), and whether it
  /// was moved. Its peak's reciprocal is the brightness limit at xy.
  KnotValues smooth_shape(Chromaticity xy, bool* moved = nullptr) const;

  /// XYZ (Y(white) = 1) of a knot spectrum seen as a reflectance under the space's white.
  Xyz xyz_of(const KnotSamples& samples) const { return colorimetry_.xyz_of(samples.knots()); }
  /// Linear RGB of a reflectance lit by the space's white: the round trip of upsample_reflectance.
  Rgb rgb_of(const ReflectanceSpectrum& spectrum) const { return space_.from_xyz(xyz_of(spectrum.samples())); }

  const RgbColourSpace& space() const { return space_; }
  const KnotColorimetry& colorimetry() const { return colorimetry_; }
  const UpsamplingTable& table() const { return table_; }
  const KnotGamut& gamut() const { return gamut_; }
  /// The white illuminant's spectrum (relative power), shared with every EmissionSpectrum.
  const std::shared_ptr<const TabulatedSpectrum>& illuminant() const { return illuminant_; }

 private:
  // The knots of upsample_reflectance's spectrum for a finite, non-black `xyz` with Y > 0; `moved` tells whether
  // gamut mapping or the brightness limit changed the colour.
  KnotValues reflectance_knots(const Xyz& xyz, bool* moved) const;
  // The fast path's Y = 1 coefficients of chromaticity xy(xyz), moved to the usable gamut's edge if outside.
  BasisCoefficients smooth_coefficients(const Xyz& xyz, bool* moved, SmoothShapeBounds* bounds) const;

  RgbColourSpace space_;
  std::shared_ptr<const TabulatedSpectrum> illuminant_;
  KnotColorimetry colorimetry_;
  UpsamplingTable table_;
  KnotGamut gamut_;
  // Built by the first basis() call (double-checked: the atomic pointer is set after the basis is complete).
  struct LazyBasis {
    std::mutex mutex;
    std::unique_ptr<const UpsamplingBasis> basis;
    std::atomic<const UpsamplingBasis*> built{nullptr};
  };
  std::unique_ptr<LazyBasis> lazy_basis_ = std::make_unique<LazyBasis>();
  const UpsamplingBasis& build_basis() const;
  double emission_scale_;  // 1 / (K_m Σ W ȳ Δλ): radiance per unit luminance of W
};

}  // namespace rimu
