// The two kinds of upsampled spectra: a reflectance (bounded by 1) and an emission (unbounded, illuminant-shaped).
// They are separate types so that a light can never be handed an albedo's spectrum, nor a material a light's.
#pragma once

#include <memory>
#include <string>

#include "spectral/spectra/tabulated_spectrum.h"
#include "spectral/upsampling/upsampling_knots.h"

namespace rimu {

/// Knot values in single precision, padded to 96 so the upper neighbour of the last knot can be read.
/// Evaluating one is the per-sample hot path: no allocation, no locks, four lanes at once.
class KnotSamples {
 public:
  KnotSamples() { values_.fill(0.0f); }
  /// Rounds `knots` to float; the pad repeats the last knot.
  explicit KnotSamples(const KnotValues& knots);

  /// Linear interpolation between knots at the four wavelengths; constant beyond 360 and 830 nm.
  Float4 sample(Float4 lambda_nm) const {
    const Float4 x = clamp((lambda_nm - Float4(float(kUpsampleFirstKnotNm))) * Float4(float(1.0 / kUpsampleKnotSpacingNm)),
                           Float4(0.0f), Float4(float(kUpsampleKnotCount - 1)));
    const Float4 base = floor(x);
    const Float4 t = x - base;
    const __m128i index = _mm_cvttps_epi32(base.v);
    const float* v = values_.data();
    const int i0 = _mm_cvtsi128_si32(index), i1 = _mm_extract_epi32(index, 1), i2 = _mm_extract_epi32(index, 2),
              i3 = _mm_extract_epi32(index, 3);
    const Float4 lo(v[i0], v[i1], v[i2], v[i3]);
    const Float4 hi(v[i0 + 1], v[i1 + 1], v[i2 + 1], v[i3 + 1]);
    return mul_add(t, hi - lo, lo);
  }
  /// The same at one wavelength, in double (colorimetry, setup).
  double value(double lambda_nm) const;
  /// Knot i's value.
  float knot(int i) const { return values_[i]; }
  /// All knots in double, for colorimetry.
  KnotValues knots() const;
  float max_value() const;
  float min_value() const;

 private:
  alignas(16) std::array<float, kUpsampleKnotCount + 1> values_;
};

/// A reflectance (or transmittance) factor upsampled from RGB: a knot spectrum with every value in [0, 1].
class ReflectanceSpectrum final : public Spectrum {
 public:
  ReflectanceSpectrum() = default;
  /// `knots` must lie in [0, 1] (asserted); made by RgbUpsampler::upsample_reflectance.
  explicit ReflectanceSpectrum(const KnotValues& knots);

  double value(double lambda_nm) const override { return samples_.value(lambda_nm); }
  SampledSpectrum sample(const SampledWavelengths& lambda) const override { return samples_.sample(lambda.lambda_nm()); }
  /// sample() without the virtual call, for code that holds the concrete type.
  SampledSpectrum evaluate(const SampledWavelengths& lambda) const { return samples_.sample(lambda.lambda_nm()); }
  double max_value() const override { return samples_.max_value(); }
  std::string describe() const override { return "upsampled reflectance"; }
  const KnotSamples& samples() const { return samples_; }

 private:
  KnotSamples samples_;
};

/// An emission spectrum upsampled from RGB: S(λ) = k · s(λ) · W(λ), the colour space's white illuminant W shaped by
/// a smooth factor s ≥ 0 (a reflectance-like curve, unbounded above) and scaled by k. Units: spectral radiance in
/// W/(m²·sr·nm) when the RGB's luminance Y is read as cd/m² (see RgbUpsampler::upsample_emission).
class EmissionSpectrum final : public Spectrum {
 public:
  EmissionSpectrum() = default;
  EmissionSpectrum(const KnotValues& shape, double scale, std::shared_ptr<const TabulatedSpectrum> illuminant);

  double value(double lambda_nm) const override;
  SampledSpectrum sample(const SampledWavelengths& lambda) const override { return evaluate(lambda); }
  /// sample() without the virtual call.
  SampledSpectrum evaluate(const SampledWavelengths& lambda) const {
    if (!illuminant_) return Float4(0.0f);
    return Float4(scale_) * shape_.sample(lambda.lambda_nm()) * illuminant_->sample(lambda);
  }
  double max_value() const override;
  std::string describe() const override;
  /// The smooth factor s (knots) and the scale k.
  const KnotSamples& shape() const { return shape_; }
  float scale() const { return scale_; }

 private:
  KnotSamples shape_;
  float scale_ = 0.0f;
  std::shared_ptr<const TabulatedSpectrum> illuminant_;
};

}  // namespace rimu
