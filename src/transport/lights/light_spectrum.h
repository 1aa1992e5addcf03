// A light's emission spectrum: a spectral shape times one scale factor.
//
// The shape and the scale are kept apart on purpose. The scene loader builds the shape (blackbody, daylight, CSV,
// upsampled RGB...) and sets the scale ONCE at load time: in this issue from a radiometric value, later (issue 5)
// from lumens, candela, lux or nits through K_m ∫ S V dλ. Nothing per-sample ever rescales a light.
#pragma once

#include "spectral/spectra/spectrum.h"

namespace rimu {

class LightSpectrum {
 public:
  /// scale × shape(λ). The unit is the light's: W/(sr·nm) for point/spot intensity, W/(m²·nm) for distant
  /// irradiance, W/(m²·sr·nm) for area/environment radiance. `scale` must be finite and ≥ 0 (asserted: the loader
  /// reports bad user values with their key). Cost: one 1 nm integration of the shape over 360-830 nm.
  LightSpectrum(SpectrumPtr shape, double scale);

  /// scale × shape at the four wavelengths (per sample).
  SampledSpectrum sample(const SampledWavelengths& lambda) const { return shape_->sample(lambda) * Float4(float(scale_)); }
  /// scale × shape at one wavelength (setup and tests).
  double value(double lambda_nm) const { return scale_ * shape_->value(lambda_nm); }
  /// ∫ scale·shape(λ) dλ over 360-830 nm: the trapezoid rule at 1 nm (exact for piecewise-linear tables on a
  /// 1 nm grid). Colorimetry uses CIE 15's rectangle sum instead; for power, the trapezoid gives exactly 470·c for
  /// a constant c, which is what the analytic tests compare against.
  double integral_360_830() const { return scale_ * shape_integral_; }

  double scale() const { return scale_; }
  const SpectrumPtr& shape() const { return shape_; }
  bool is_black() const { return !(integral_360_830() > 0.0); }

 private:
  SpectrumPtr shape_;
  double scale_;
  double shape_integral_;
};

}  // namespace rimu
