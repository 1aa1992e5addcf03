// A spectrum given as (wavelength, value) samples, linearly interpolated.
#pragma once

#include <string>
#include <vector>

#include "spectral/spectra/spectrum.h"

namespace rimu {

class CsvTable;

/// What a tabulated spectrum is outside its first and last wavelength.
enum class Extrapolation {
  zero,   ///< 0 outside: emission tables (a lamp measured over 380-780 nm emits nothing we know of beyond).
  clamp,  ///< the nearest end value: reflectances and optical constants (CIE 15:2004 §7.2.2.1 recommends
          ///< extending measured data by its nearest value).
};

/// Linear interpolation between samples at any spacing (strictly increasing wavelengths).
///
/// When every sample sits on a whole nanometre, the table is also kept resampled at 1 nm over 360-830 nm;
/// linear interpolation of that copy is the same piecewise-linear function (the knots are a subset of the
/// integers), so sample() can index it directly instead of searching: the fast path for the per-sample loop.
class TabulatedSpectrum final : public Spectrum {
 public:
  /// Throws InputError (with `name` as the source) if the sizes differ, fewer than 2 samples are given, a value
  /// is not finite, or the wavelengths are not strictly increasing.
  TabulatedSpectrum(std::vector<double> lambda_nm, std::vector<double> values, Extrapolation extrapolation,
                    std::string name);
  /// Column `column` of a CSV table whose first column is the wavelength in nm; errors name the file and line.
  static TabulatedSpectrum from_csv(const CsvTable& table, const std::string& column, Extrapolation extrapolation);

  double value(double lambda_nm) const override;
  SampledSpectrum sample(const SampledWavelengths& lambda) const override;
  double max_value() const override { return max_value_; }
  std::string describe() const override { return name_; }

  const std::vector<double>& wavelengths_nm() const { return lambda_; }
  const std::vector<double>& values() const { return values_; }
  double min_value() const { return min_value_; }
  Extrapolation extrapolation() const { return extrapolation_; }

 private:
  std::vector<double> lambda_;
  std::vector<double> values_;
  Extrapolation extrapolation_;
  std::string name_;
  double max_value_ = 0, min_value_ = 0;
  std::vector<float> dense_1nm_;  // values at 360, 361, ..., 830 nm (+1 pad); empty if the knots are not whole nm
};

}  // namespace rimu
