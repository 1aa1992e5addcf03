// Adaptive sampling (`rimu --noise-threshold 0.01`): which pixels still need samples and how many each takes in the
// next pass, decided between passes from the film's sums of two half buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film/film.h"
#include "spectral/colour_spaces/matrix3.h"

namespace rimu {

struct AdaptiveSamplingSettings {
  double noise_threshold = 0.01;  ///< the relative standard error of a pixel's luminance at which it may stop
  int min_spp = 16;               ///< no pixel stops before this many samples (adaptive_min_spp)
  int dilation_px = 2;            ///< a pixel stops only when every pixel this close (a square) has converged
  int max_spp = 0;                ///< a pixel stops at this many samples (0: no maximum, e.g. a time budget alone)
  /// After the minimum, a pass of s samples per pixel takes at most this many times s in any one pixel: one pass's
  /// error estimate, wrong by luck, cannot pour a whole pass into a few pixels.
  int max_pass_share = 8;
  int allocation_radius_px = 1;  ///< the error that shares out a pass is the RMS over a (2r + 1)² square
  /// The neighbourhood's floor on each pixel's error (see AdaptiveSampling): its share of what the pixel's samples
  /// would give at the neighbourhood's mean relative variance per sample, and the neighbourhood's radius (a square).
  double neighbourhood_share = 0.25;
  int neighbourhood_radius_px = 3;
};

/// The samples every pixel takes before any may stop, for a render of at most `max_spp`: max(16, max_spp / 8).
/// Fewer, and the two half buffers are too noisy to tell a dark converged pixel from an unlucky one.
int adaptive_min_spp(int max_spp);

/// The active pixels of an adaptive render and the error estimate that decides them.
///
/// Estimate: the renderer's passes alternate between two half buffers (even and odd passes). After each pass the
/// film's channel sums and weight sum of every pixel are compared with their values before it, and the difference
/// goes to the pass's half. The threshold reads luminance (Y for XYZ films, R + G + B for camera films). With half means a, b over n_a, n_b samples,
/// the pixel's mean over n = n_a + n_b samples has the standard error estimated by
///   SE = |a − b| / sqrt((1/n_a + 1/n_b) · n)      (= |a − b| / 2 for n_a = n_b),
/// since Var(a − b) = σ²(1/n_a + 1/n_b) and SE² = σ²/n. The relative error is SE / mean (0 for a black pixel with
/// no variation). One pixel's |a − b| is itself a one-sample estimate, so the decision uses the root mean square of
/// the relative errors over the pixel's 3×3 neighbourhood; a pixel stops once that is ≤ the threshold for it and
/// for every pixel within dilation_px (no isolated stopped pixels: no blotches). A stopped pixel stays stopped:
/// its sums stop changing, and its value, sum / its own weight sum, stays an unbiased estimate.
///
/// The neighbourhood's floor: a pixel whose light comes through rare paths (a caustic, a gap) shows no error at all
/// until one of its samples finds one: both halves agree, and the pixel would stop, or take one sample a pass, long
/// before it had the samples its variance needs. Its neighbours, pooled, find those paths many times sooner. So
/// the error a pixel is judged by, for stopping and for its share, is at least
///   relative error² ≥ neighbourhood_share · V / n,   V = Σ σ_j² / Σ μ_j²
/// over the (2·neighbourhood_radius_px + 1)² square around it, with σ_j² = SE_j² · n_j each pixel's variance per
/// sample and μ_j its mean (the same for R, G, B in the allocation): what n samples would give at the
/// neighbourhood's relative variance per sample, times a share (¼: the error is at least half of that). Pooled
/// sums, not a mean of the pixels' relative variances, so that a nearly black pixel's huge relative error does not
/// lift its neighbours'. The floor falls as 1/n, so a pixel whose neighbourhood is noisy still stops, but only
/// once its own samples are enough for that noise; where the neighbourhood is quiet it is no higher than the
/// pixels' own errors and changes nothing.
///
/// Where the samples go (plan_pass): until the minimum every active pixel takes every pass's samples. From then
/// on a pass of s samples per pixel is s times the active pixels' count, shared among them by their noise and
/// their cost. The image's relMSE, Σ σ_i² / (n_i μ_i²) over pixels with per-sample standard deviation σ_i, mean μ_i
/// and n_i samples, is smallest for a given time Σ n_i c_i, with c_i a sample's cost in pixel i, at
/// n_i ∝ σ_i / (μ_i sqrt(c_i)) (Lagrange). σ_i² / μ_i² is estimated from the pixel's own samples' second moments
/// (add_sample_value), over linear R, G, B (each channel's mean at least 1 % of the largest; a camera film's own
/// channels), averaged over the (2·allocation_radius_px + 1)² neighbourhood and at least the neighbourhood's floor
/// times n: relMSE counts every channel, so chroma noise draws samples too. (Not from the two halves: their
/// difference is one degree of freedom however many samples they hold, so shares decided from it stayed as noisy
/// after thousands of samples as after 32; the second moments have n − 1.) The cost is the rays the pixel's
/// samples traced per sample (render/scene/ray_tally.h: a dark corner's long paths cost more than a sample of the
/// sky) plus kSampleOverheadRays for what a sample costs besides its rays (add_rays); counted, not timed, so the
/// counts stay deterministic. Each pass moves the counts toward that: every active pixel gets one sample (no
/// pixel starves; both halves keep getting samples), the rest goes to the pixels below their target share in
/// proportion to how far below they are, at most max_pass_share · s per pixel; what capped pixels cannot take
/// goes to the others, and what is left once every target is met goes in proportion to the targets, so a pass
/// always spends s samples per active pixel (a pass that spent less would make a time budget run more passes, and
/// their one sample per pixel would add up to uniform sampling). Fractions carry over to the pixel's next pass.
/// Every pixel's samples are its own sample indices 0, 1, 2, … in order, whatever it takes per pass.
///
/// Deterministic: decided from the film's sums on the calling thread between passes, so the image depends on the
/// seed and the settings, not on the threads.
class AdaptiveSampling {
 public:
  AdaptiveSampling(const Film& film, const AdaptiveSamplingSettings& settings);

  /// Before each pass of the renderer's schedule (`pass_samples` per pixel, render/renderer.h): how many samples
  /// each active pixel takes in it (pass_samples() below). Returns the pass's samples over all pixels. Cost: a few
  /// passes over the film's pixels.
  uint64_t plan_pass(int pass_samples);

  /// After each whole pass: moves the pass into its half buffer and, from min_spp on, stops the pixels that
  /// converged; a pixel also stops at max_spp. `samples_end` is the renderer's end of the pass in its schedule
  /// (which, with unequal counts, is no pixel's count). Returns the pixels still active. Cost: a few passes over the
  /// film's pixels.
  size_t after_pass(const Film& film, int samples_end);

  /// Whether pixel (x, y) (inside the film's crop window) takes the next pass's samples.
  bool active(int x, int y) const { return active_[index(x, y)] != 0; }
  size_t active_count() const { return active_count_; }
  /// The renderer, after pixel (x, y)'s samples of a pass: the rays they traced (rays_traced_by_this_thread()'s
  /// difference). Tiles are disjoint, so threads write different pixels.
  void add_rays(int x, int y, uint64_t rays) { rays_[index(x, y)] += rays; }
  /// The renderer, after each sample of pixel (x, y): the sample's own value in the film's channels (its share of
  /// the film's sums over its share of the weight; not called for a sample of weight 0). Its square goes into the
  /// pixel's second moments, from which the pass's shares are decided (plan_pass).
  void add_sample_value(int x, int y, const double channels[3]) {
    double* m = &moments_[kMoments * index(x, y)];
    for (int c = 0; c < 3; ++c) {
      const double v = to_rgb_(c, 0) * channels[0] + to_rgb_(c, 1) * channels[1] + to_rgb_(c, 2) * channels[2];
      m[c] += v;
      m[3 + c] += v * v;
    }
    m[6] += 1.0;
  }
  /// What a sample costs besides the rays it traces (camera ray generation, wavelengths, the film's splat), in
  /// rays: a sample of pixel i is taken to cost rays_i / samples_i + this.
  static constexpr double kSampleOverheadRays = 1.0;

  /// The samples pixel (x, y) received: its next pass takes its sample indices from this one on.
  int samples(int x, int y) const { return samples_[index(x, y)]; }
  /// The samples pixel (x, y) takes in the pass planned last (0 once it stopped).
  int pass_samples(int x, int y) const { return active_[index(x, y)] ? pass_samples_[index(x, y)] : 0; }
  /// The most samples any pixel received, and their mean over the pixels.
  int max_samples() const;
  double mean_samples() const;
  /// Its relative standard error after the last pass (the 3×3 root mean square the decision used).
  float relative_error(int x, int y) const { return error_[index(x, y)]; }
  const AdaptiveSamplingSettings& settings() const { return settings_; }

 private:
  size_t index(int x, int y) const { return size_t(y - bounds_.y0) * size_t(bounds_.width()) + size_t(x - bounds_.x0); }
  void update_errors();

  PixelBounds bounds_;
  AdaptiveSamplingSettings settings_;
  bool camera_film_;
  int passes_ = 0, samples_end_ = 0;
  bool spreading_ = false;  ///< past the minimum: passes share their samples by error (plan_pass)
  Matrix3 to_rgb_;  ///< film channels to linear sRGB (identity for a camera film): the colour error's channels
  std::vector<double> last_channels_, last_weight_;   ///< the film's sums after the previous pass (3 channels a pixel)
  std::vector<double> half_channels_[2], half_weight_[2];
  std::vector<int> samples_, pass_samples_;
  std::vector<uint64_t> rays_;   ///< the rays each pixel's samples traced (add_rays): their cost
  /// Per pixel: Σ v, Σ v² of its samples' linear R, G, B (add_sample_value), and their count.
  static constexpr size_t kMoments = 7;
  std::vector<double> moments_;
  std::vector<double> carried_;  ///< each pixel's fraction of a sample not yet taken (plan_pass)
  std::vector<float> error_;
  std::vector<double> relative_squared_;  ///< each pixel's own squared relative error of luminance (∞: none yet)
  /// The neighbourhood's floor on a pixel's squared relative error over linear R, G, B (plan_pass multiplies it by
  /// the pixel's samples: a floor on its relative variance per sample).
  std::vector<double> colour_floor_;
  std::vector<uint8_t> active_;
  /// plan_pass's and update_errors' per-pixel working arrays, kept between passes: allocated anew each pass, their
  /// ~1.5 MB (at 80 × 45) went back to the system and came back as page faults every pass, 8 % of a window-and-
  /// corridor render's CPU time at 512 spp (docs/benchmarks.md, "Adaptive sampling").
  struct Scratch {
    std::vector<double> per_sample, deviation, window, extra, room, shortfall;
    std::vector<double> variance[4], mean_squared[4], pooled[4], means, luminance_window, rows;
    std::vector<uint8_t> converged;
  } scratch_;
  size_t active_count_;
};

}  // namespace rimu
