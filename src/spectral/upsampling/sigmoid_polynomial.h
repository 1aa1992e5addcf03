// RGB → spectrum as a sigmoid of a quadratic in wavelength (Jakob & Hanika 2019, "A Low-Dimensional Function Space
// for Efficient Spectral Upsampling", Computer Graphics Forum 38(2)): the upsampling pbrt-v4 uses, fitted per colour.
#pragma once

#include <vector>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/error.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

/// s(λ) = S(c0·λ² + c1·λ + c2) with λ in nm and S(x) = ½ + x / (2√(1 + x²)), a smooth map of ℝ onto (0, 1).
/// The three coefficients hold every such spectrum; the constants 0 and 1 are the limits c2 → ∓∞ (c0 = c1 = 0),
/// kept as c2 = ∓∞ and evaluated exactly.
struct SigmoidPolynomial {
  double c0 = 0, c1 = 0, c2 = 0;

  /// The constant spectrum v ∈ [0, 1]: c2 = (v − ½)/√(v(1 − v)), for which S(c2) = v (±∞ at 0 and 1).
  static SigmoidPolynomial constant(double v);
  /// s(λ) ∈ [0, 1].
  double value(double lambda_nm) const;
};

/// A fitted spectrum: scale · polynomial(λ), and how far its colour lies from the requested one.
struct SigmoidSpectrum {
  SigmoidPolynomial polynomial;
  double scale = 1;        ///< 1 for an albedo; 2·max(r, g, b) for an unbounded RGB (0 for black)
  double delta_e_ab = 0;   ///< CIE 1976 ΔE*ab between the requested colour (of rgb / scale) and the fit's
  double value(double lambda_nm) const { return scale * polynomial.value(lambda_nm); }
};

/// Fits sigmoid polynomials to the RGB of one colour space, as pbrt-v4's RGBAlbedoSpectrum and
/// RGBUnboundedSpectrum do (pbrt reads its coefficients from a precomputed grid; here each colour is fitted on
/// demand, about 1 ms, so callers that see a colour often should keep the result).
///
/// The colour of a spectrum s is its CIE 1931 2° XYZ as a reflectance under the space's white illuminant (the
/// spectrum upsampling_illuminant gives: D65, E or the ACES white), on a 1 nm grid over 360–830 nm, normalised to
/// Y = 1 for s = 1; its CIELAB takes that illuminant's XYZ as the white. The target's CIELAB takes the space's
/// own RGB → XYZ and the space's white (Y = 1), so RGB (1, 1, 1) and the constant 1 are both L* = 100, a* = b* = 0
/// exactly, whatever the few 1e-5 by which the tabulated illuminant misses the space's stated white chromaticity.
///
/// The fit minimises the CIELAB difference (three residuals, three unknowns) by Gauss–Newton steps damped
/// Levenberg–Marquardt style (a plain Newton step with a line search stalled on saturated colours, where the
/// sigmoid flattens and the Jacobian is nearly singular), in the variable t = (λ − 360)/470 for conditioning. It
/// starts from the constant ½ and walks the target along the straight RGB line from (½, ½, ½) to the colour in 16
/// steps, each solved from the previous one (a continuation, as the paper's table optimiser walks its grid from
/// the centre), so saturated colours converge from a nearby solution. ~1 ms a colour.
class SigmoidFitter {
 public:
  /// Throws InputError if the space's white has no illuminant (upsampling_white_for).
  SigmoidFitter(SpectralLibrary& library, const RgbColourSpace& space);

  /// An albedo in (0, 1) at every wavelength whose colour is `rgb` (pbrt's RGBAlbedoSpectrum). Each component must
  /// be finite and within [0, 1] (InputError at `where` otherwise). Greys (r = g = b) are the exact constant.
  /// Colours no spectrum in (0, 1) can reach (beyond the gamut of such spectra) come back as the closest fit found,
  /// with their delta_e_ab.
  SigmoidSpectrum fit_albedo(const Rgb& rgb, const SourceLocation& where = {}) const;

  /// pbrt's RGBUnboundedSpectrum: m = 2·max(r, g, b), the albedo fit of rgb/m, times m (black gives 0). Components
  /// must be finite and ≥ 0 (InputError at `where`).
  SigmoidSpectrum fit_unbounded(const Rgb& rgb, const SourceLocation& where = {}) const;

  /// Linear RGB of the spectrum `s` seen as a reflectance under the space's white (scale included).
  Rgb rgb_of(const SigmoidSpectrum& s) const;
  /// CIE 1976 ΔE*ab between `rgb` and the colour of `s`, both as above.
  double delta_e_ab(const Rgb& rgb, const SigmoidSpectrum& s) const;

  const RgbColourSpace& space() const { return space_; }

 private:
  // XYZ (Y = 1 for the constant 1) of the polynomial's spectrum.
  Xyz xyz_of(const SigmoidPolynomial& p) const;
  // Runs the Gauss–Newton fit for an rgb within [0, 1]³ that is not grey.
  SigmoidSpectrum fit(const Rgb& rgb) const;

  RgbColourSpace space_;
  std::vector<double> lambda_nm_;       // the 1 nm grid
  std::vector<double> wx_, wy_, wz_;    // x̄·illuminant (and ȳ, z̄) per grid point, Σ wy = 1
  Xyz illuminant_white_;                // Σ w: the XYZ of the constant 1
  Xyz space_white_;                     // the space's white at Y = 1
};

}  // namespace rimu
