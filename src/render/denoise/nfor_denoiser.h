// A Monte Carlo denoiser from published, non-learned methods: nonlinearly weighted first-order regression on the
// render's features (Bitterli et al. 2016, "Nonlinearly Weighted First-order Regression for Denoising Monte Carlo
// Renderings", NFOR), simplified as docs/rendering.md ("Denoising") describes.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace rimu {

/// What the denoiser reads, per pixel of a width × height image, row by row. Colours are in the film's space
/// (CIE XYZ or camera RGB), three interleaved channels.
struct DenoiseInput {
  int width = 0, height = 0;
  std::array<std::vector<float>, 2> halves;  ///< the means of the even and of the odd samples (3 channels)
  std::vector<float> variance;               ///< variance of the whole beauty's mean (channels averaged; 1 channel)
  std::vector<float> albedo;                 ///< 3 channels
  std::vector<float> normal;                 ///< 3 channels
  std::vector<float> depth;                  ///< 1 channel, any unit (normalised by its largest value)
  /// The variances of the features' means (1 channel each, components averaged).
  std::vector<float> albedo_variance, normal_variance, depth_variance;
};

struct DenoiseSettings {
  /// The regression's window: (2r + 1)² pixels. 11×11 rather than NFOR's 19×19 (r = 9): a larger window fits one
  /// linear model of colour on the features across more surfaces, and where colour is not linear in the albedo
  /// across them (a colour chart's patches) the fit misses a dim channel (docs/benchmarks.md, "Denoising").
  int window_radius = 5;
  /// The NL-means colour patch: (2p + 1)² pixels. 3×3 rather than NFOR's 7×7: at the benchmarks' 96×54 a lamp is
  /// 3 pixels tall, and a larger patch makes its neighbours look alike (docs/benchmarks.md, "Denoising").
  int patch_radius = 1;
  /// The colour bandwidths k of the NL-means weights, one filtered candidate each; every pixel takes the candidate
  /// whose relative error, estimated from the two halves (render/denoise/denoise_selection.h), is lowest at it.
  /// NFOR's choice: 0.5 and 1.
  std::vector<double> colour_bandwidths{0.5, 1.0};
  /// Also weigh neighbours by their features' distance (Rousselle, Manzi & Zwicker 2013's joint weights, the
  /// smaller of the colour and the feature weight). NFOR weighs by colour alone; here the feature weights are on by
  /// default because at low spp the colour weights alone let a noisy lit wall bleed into the black beyond a scene's
  /// edge, where a relative error measure punishes it most (docs/benchmarks.md, "Denoising").
  bool feature_weights = true;
  /// The feature bandwidths k_f: every pair of a colour and a feature bandwidth is a candidate filter. A loose one
  /// (3: features barely part neighbours the colour weights accept) for smooth regions lit unevenly, a strict one
  /// (0.5) for edges between surfaces whose colours differ where the features differ little.
  std::vector<double> feature_bandwidths{3.0, 0.5};
  /// The box the candidates' error estimates are averaged over before the choice. 0: each pixel's own estimates (a
  /// box across an edge lets the smooth side's choice decide the edge's pixels; docs/benchmarks.md, "Denoising").
  int selection_radius = 0;
  /// The features' NL-means prefilter (NFOR's section 5.1): window radius (0: off) and bandwidth.
  int feature_prefilter_radius = 3;
  double feature_prefilter_bandwidth = 1.0;
  /// NFOR's second pass (section 5.4): the mean of the two filtered halves filtered again, guided by itself, with
  /// the variance the filtered halves' difference shows, at this colour bandwidth and the last feature bandwidth.
  bool second_pass = true;
  double second_pass_bandwidth = 2.0;
  /// The result is kept within the noisy value ± this many standard errors (0: off); see docs/rendering.md.
  double clamp_sigmas = 5.0;
  int threads = 0;                 ///< 0: every core (oneTBB)
};

struct DenoiseResult {
  std::vector<float> image;                 ///< the denoised beauty, 3 channels
  std::vector<int> chosen;                  ///< per pixel, the index of the colour bandwidth chosen
  double seconds = 0.0;
};

/// Checks the input's sizes (every buffer the right length for width × height, both sizes positive): throws
/// InputError naming `where` otherwise.
void check_denoise_input(const DenoiseInput& input, const std::string& where);

/// Denoises: the features are prefiltered; for each candidate bandwidth, each half is filtered with weights computed
/// from the other half (so the weights do not see the noise they average), by a weighted first-order regression of
/// the colour on the features around each pixel; each pixel takes the candidate whose relative error the halves
/// estimate lowest, the mean of its two filtered halves; a second pass filters that mean again, and the result is
/// clamped to the noisy value ± clamp_sigmas standard errors. Non-finite inputs are read as 0; the output is finite.
/// Cost: about (2r+1)² · 250 flops per pixel and candidate, and a quarter of that for the second pass, parallel over
/// rows.
DenoiseResult denoise(const DenoiseInput& input, const DenoiseSettings& settings = {});

}  // namespace rimu
