#include "spectral/spectra/tabulated_spectrum.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "spectral/io/csv_table.h"
#include "spectral/error.h"
#include "spectral/spectra/spectrum_values_check.h"
#include "spectral/spectra/spectral_value_range.h"
#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {

std::string spectral_value_range_error(double value) {
  const double magnitude = std::abs(value);
  if (value == 0.0 || (magnitude >= kMinSpectralValueMagnitude && magnitude <= kMaxSpectralValueMagnitude)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return std::string(text) + (magnitude < kMinSpectralValueMagnitude ? " is nonzero but smaller" : " is larger") +
         " in magnitude than Rimu accepts for a spectral value (0, or 1e-30 to 1e30: beyond, colour integrals "
         "underflow or overflow); scale the data";
}

TabulatedSpectrum::TabulatedSpectrum(std::vector<double> lambda_nm, std::vector<double> values,
                                     Extrapolation extrapolation, std::string name)
    : lambda_(std::move(lambda_nm)), values_(std::move(values)), extrapolation_(extrapolation), name_(std::move(name)) {
  if (lambda_.size() != values_.size())
    throw InputError({name_, 0, ""}, "wavelength and value lists differ in length");
  if (lambda_.size() < 2) throw InputError({name_, 0, ""}, "a tabulated spectrum needs at least two samples");
  for (size_t i = 0; i < lambda_.size(); ++i) {
    if (!std::isfinite(lambda_[i]) || !std::isfinite(values_[i]))
      throw InputError({name_, 0, ""}, "sample " + std::to_string(i) + " is not a finite number");
    if (i > 0 && !(lambda_[i] > lambda_[i - 1]))
      throw InputError({name_, 0, ""}, "wavelengths must increase strictly; " + std::to_string(lambda_[i]) +
                                           " nm follows " + std::to_string(lambda_[i - 1]) + " nm");
  }
  max_value_ = *std::max_element(values_.begin(), values_.end());
  min_value_ = *std::min_element(values_.begin(), values_.end());
  if (extrapolation_ == Extrapolation::zero) {
    max_value_ = std::max(max_value_, 0.0);
    min_value_ = std::min(min_value_, 0.0);
  }

  const bool whole_nm =
      std::all_of(lambda_.begin(), lambda_.end(), [](double l) { return l == std::floor(l); });
  if (whole_nm) {
    const int count = int(kLambdaMaxNm - kLambdaMinNm) + 2;  // one pad so index+1 is always valid
    dense_1nm_.resize(count);
    for (int i = 0; i < count; ++i) dense_1nm_[i] = float(value(kLambdaMinNm + i));
  }
}

TabulatedSpectrum TabulatedSpectrum::from_csv(const CsvTable& table, const std::string& column,
                                              Extrapolation extrapolation) {
  std::vector<double> lambda = table.numbers(0);
  std::vector<double> values = table.numbers(table.column_index(column));
  check_wavelengths_nm(lambda, [&](size_t row) { return SourceLocation{table.name(), table.line_of_row(row), ""}; });
  for (size_t r = 0; r < values.size(); ++r)
    if (const std::string why = spectral_value_range_error(values[r]); !why.empty())
      throw InputError({table.name(), table.line_of_row(r), ""}, "column '" + column + "': " + why);
  return TabulatedSpectrum(std::move(lambda), std::move(values), extrapolation, table.name() + " [" + column + "]");
}

double TabulatedSpectrum::value(double lambda_nm) const {
  if (!(lambda_nm >= lambda_.front())) return extrapolation_ == Extrapolation::zero ? 0.0 : values_.front();
  if (!(lambda_nm <= lambda_.back())) return extrapolation_ == Extrapolation::zero ? 0.0 : values_.back();
  const size_t hi = size_t(std::upper_bound(lambda_.begin(), lambda_.end(), lambda_nm) - lambda_.begin());
  if (hi >= lambda_.size()) return values_.back();
  const size_t lo = hi - 1;
  const double t = (lambda_nm - lambda_[lo]) / (lambda_[hi] - lambda_[lo]);
  return values_[lo] + t * (values_[hi] - values_[lo]);
}

SampledSpectrum TabulatedSpectrum::sample(const SampledWavelengths& lambda) const {
  if (dense_1nm_.empty()) return Spectrum::sample(lambda);
  // Fast path: index the 1 nm copy. Wavelengths outside 360-830 are clamped into the table's ends, which is
  // where value() would take them for both extrapolation rules only if the table covers 360-830; sampled
  // wavelengths always lie inside that range, so this is exact for them.
  const Float4 x = clamp(lambda.lambda_nm() - Float4(float(kLambdaMinNm)), Float4(0.0f),
                         Float4(float(kLambdaMaxNm - kLambdaMinNm)));
  const Float4 base = floor(x);
  const Float4 t = x - base;
  alignas(16) int index[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(index), _mm_cvttps_epi32(base.v));
  const float* d = dense_1nm_.data();
  const Float4 lo(d[index[0]], d[index[1]], d[index[2]], d[index[3]]);
  const Float4 hi(d[index[0] + 1], d[index[1] + 1], d[index[2] + 1], d[index[3] + 1]);
  const Float4 value = mul_add(t, hi - lo, lo);
  if (extrapolation_ == Extrapolation::clamp) return value;  // the 1 nm copy already holds the end values
  // Zero extrapolation is a step at the end knots; the 1 nm copy would ramp over the nanometre outside them.
  const Float4 l = lambda.lambda_nm();
  const Mask4 inside = (l >= Float4(float(lambda_.front()))) & (l <= Float4(float(lambda_.back())));
  return select(inside, value, Float4(0.0f));
}

}  // namespace rimu
