// The denoiser's inputs made ready for filtering (render/denoise/nfor_denoiser.h): sanitised, the depth normalised,
// the features prefiltered; and the clamp of its output to the input's noise.
#pragma once

#include <array>
#include <vector>

#include "render/denoise/nfor_denoiser.h"

namespace rimu {

constexpr int kDenoiseFeatures = 7;  // albedo (3), normal (3), depth (1)

/// The pixel-wise inputs the filter reads, sanitised and normalised.
struct PreparedDenoiseInput {
  int width, height;
  std::array<std::vector<float>, 2> halves;  // 3 channels
  std::vector<float> half_variance;          // variance of one half's mean ≈ twice the whole's
  std::vector<float> features;               // kDenoiseFeatures per pixel
  std::array<std::vector<float>, 3> feature_variance;
};

/// Copies the input with every non-finite value read as 0, the whole beauty's variance doubled to a half's, and
/// depth (and its variance) in units of the image's largest depth.
PreparedDenoiseInput prepare_denoise_input(const DenoiseInput& in);

/// Prefilters the features (NFOR's section 5.1, with the features' own variance in place of their half buffers): an
/// NL-means average over a (2r + 1)² window whose weight is exp(−max(0, d)), d the largest over albedo, normal and
/// depth of the variance-cancelled squared distance of 3×3 patches over k²(Var p + Var q). A noiseless feature
/// (variance 0) differs from every other value by infinitely many "sigmas" and stays as it is; a noisy one (the
/// albedo of a pixel that only one of its 16 samples saw a wall in) is averaged with its like, so the regression
/// below does not trust its sampling noise as a partial coverage. The features' variances become the prefiltered
/// means' own, Σ w² Var / (Σ w)² (the weights read as fixed), so that the feature weights downstream compare what is
/// left of the noise rather than the raw noise: with the raw variance they let a neighbour across an edge in as
/// "within the noise" where the prefilter has already averaged the noise away.
void prefilter_features(PreparedDenoiseInput& p, int radius, double bandwidth);

/// Limits each denoised value to the noisy value ± z σ (per channel), σ² the largest of the pixel's variance, its two
/// halves' squared half-difference and the median variance of its 3×3 neighbourhood. The median keeps a pixel whose
/// few samples missed a rare bright path (variance ≈ 0) from being pinned to its too-dark noisy value; the clamp
/// catches what the filter invents beyond any plausible noise: light leaking from a bright, small emitter that the
/// features do not show (a lamp whose albedo and normal are the ceiling's) into the pixels next to it, or colour
/// spread into black pixels. It is a bias trade-off: a value the noise would put more than z σ away is pulled back.
void clamp_to_noise(const PreparedDenoiseInput& d, double sigmas, std::vector<float>& image);

}  // namespace rimu
