// A continuous spectral distribution: a function of wavelength.
#pragma once

#include <memory>
#include <string>

#include "spectral/wavelengths/sampled_wavelengths.h"

namespace rimu {

/// A spectral distribution over wavelength in nm: reflectance, spectral radiance, a colour-matching function...
/// What its values mean (unitless reflectance, W/(m²·sr·nm), relative power) is stated by whoever makes it.
class Spectrum {
 public:
  virtual ~Spectrum() = default;
  /// The value at one wavelength (exact; for colorimetry and setup, not the per-sample loop).
  virtual double value(double lambda_nm) const = 0;
  /// Values at the four sampled wavelengths (the per-sample path). The default calls value() per lane.
  virtual SampledSpectrum sample(const SampledWavelengths& lambda) const;
  /// A bound on value() over 360-830 nm (for gamut checks and sampling).
  virtual double max_value() const = 0;
  /// A short human-readable description, e.g. "blackbody 2856 K" or "CIE D65 (cie_d65_1nm.csv)".
  virtual std::string describe() const = 0;
};

using SpectrumPtr = std::shared_ptr<const Spectrum>;

/// The same value at every wavelength.
class ConstantSpectrum final : public Spectrum {
 public:
  explicit ConstantSpectrum(double value) : value_(value) {}
  double value(double) const override { return value_; }
  SampledSpectrum sample(const SampledWavelengths&) const override { return Float4(float(value_)); }
  double max_value() const override { return value_; }
  std::string describe() const override;

 private:
  double value_;
};

}  // namespace rimu
