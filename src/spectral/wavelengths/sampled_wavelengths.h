// The wavelengths a path carries: one hero and three partners, with their sampling densities.
#pragma once

#include "spectral/wavelengths/lanes.h"

namespace rimu {

/// The values of a spectral quantity at the four wavelengths of a SampledWavelengths, lane by lane.
using SampledSpectrum = Float4;

/// Four wavelengths (nm) and the density (1/nm) with which each was sampled.
///
/// Hero-wavelength sampling (Wilkie et al. 2014): lane 0, the hero, is drawn from the visible importance
/// density p(λ); the partners sit at the same primary sample rotated by a quarter of the unit interval,
/// λ_j = P⁻¹((u + j/4) mod 1). Rotating in primary-sample space (rather than in nm) keeps every lane's marginal
/// density equal to p, so each lane is an unbiased sample of p on its own, and the four stratify [0,1).
///
/// A dispersive event (a specular refraction whose direction depends on λ) can only follow one wavelength:
/// terminate_secondary() zeroes the partners' pdf and the estimator then carries the hero alone (with its
/// density divided by kLaneCount, since only one of the four stratified samples survives).
class SampledWavelengths {
 public:
  /// Hero + rotated partners from one uniform number u in [0,1), importance-sampled over 360-830 nm.
  static SampledWavelengths sample_visible(float u);
  /// Hero + rotated partners, uniform over [min_nm, max_nm); the pdf is 1/(max-min).
  static SampledWavelengths sample_uniform(float u, float min_nm, float max_nm);
  /// Four given wavelengths with given densities (tests, fixed-wavelength tools).
  SampledWavelengths(Float4 lambda_nm, Float4 pdf_per_nm) : lambda_(lambda_nm), pdf_(pdf_per_nm) {}

  Float4 lambda_nm() const { return lambda_; }
  float lambda_nm(int lane) const { return lambda_[lane]; }
  float hero_nm() const { return lambda_[0]; }
  /// Density of each lane's wavelength, per nm; zero in lanes that were terminated.
  Float4 pdf() const { return pdf_; }

  /// Keep only the hero (after a wavelength-dependent event). Idempotent.
  void terminate_secondary();
  bool secondary_terminated() const { return pdf_[1] == 0.0f && pdf_[2] == 0.0f && pdf_[3] == 0.0f; }

 private:
  Float4 lambda_;
  Float4 pdf_;
};

/// The primary sample of lane `lane` when the hero's is u: u + lane/kLaneCount, wrapped into [0, 1). Every
/// hero-wavelength sampler rotates its partners this way.
inline float rotated_primary_sample(float u, int lane) {
  const float u_lane = u + float(lane) / kLaneCount;
  return u_lane >= 1.0f ? u_lane - 1.0f : u_lane;
}

/// The visible importance density: p(λ) ∝ 1/cosh²(a(λ − 538 nm)) with a = 0.0072/nm, normalised over
/// 360-830 nm. It follows the sum of the CIE colour-matching functions closely and has a closed-form
/// inverse CDF (Radziszewski et al. 2009 use the same shape; the constants are those popularised by pbrt-v4).
float visible_wavelength_pdf(float lambda_nm);
/// The inverse CDF of visible_wavelength_pdf: maps u in [0,1) to a wavelength in [360, 830) nm.
float sample_visible_wavelength(float u);
/// Lane-wise visible_wavelength_pdf.
Float4 visible_wavelength_pdf(Float4 lambda_nm);

}  // namespace rimu
