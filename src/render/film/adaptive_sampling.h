// Adaptive sampling (`rimu --noise-threshold 0.01`): which pixels still need samples, decided between passes from
// the film's sums of two half buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film/film.h"

namespace rimu {

struct AdaptiveSamplingSettings {
  double noise_threshold = 0.01;  ///< the relative standard error of a pixel's luminance at which it may stop
  int min_spp = 16;               ///< no pixel stops before this many samples (adaptive_min_spp)
  int dilation_px = 2;            ///< a pixel stops only when every pixel this close (a square) has converged
};

/// The samples every pixel takes before any may stop, for a render of at most `max_spp`: max(16, max_spp / 8).
/// Fewer, and the two half buffers are too noisy to tell a dark converged pixel from an unlucky one.
int adaptive_min_spp(int max_spp);

/// The active pixels of an adaptive render and the error estimate that decides them.
///
/// Estimate: the renderer's passes alternate between two half buffers (even and odd passes). After each pass the
/// film's luminance sum and weight sum of every pixel (Y for XYZ films, R + G + B for camera films) are compared with
/// their values before it, and the difference goes to the pass's half. With half means a, b over n_a, n_b samples,
/// the pixel's mean over n = n_a + n_b samples has the standard error estimated by
///   SE = |a − b| / sqrt((1/n_a + 1/n_b) · n)      (= |a − b| / 2 for n_a = n_b),
/// since Var(a − b) = σ²(1/n_a + 1/n_b) and SE² = σ²/n. The relative error is SE / mean (0 for a black pixel with
/// no variation). One pixel's |a − b| is itself a one-sample estimate, so the decision uses the root mean square of
/// the relative errors over the pixel's 3×3 neighbourhood; a pixel stops once that is ≤ the threshold for it and
/// for every pixel within dilation_px (no isolated stopped pixels: no blotches). A stopped pixel stays stopped:
/// its sums stop changing, and its value, sum / its own weight sum, stays an unbiased estimate.
///
/// Deterministic: decided from the film's sums on the calling thread between passes, so the image depends on the
/// seed and the settings, not on the threads.
class AdaptiveSampling {
 public:
  AdaptiveSampling(const Film& film, const AdaptiveSamplingSettings& settings);

  /// After each whole pass, with `samples_end` the end of the samples now in the film: moves the pass into its half
  /// buffer and, from min_spp on, stops the pixels that converged. Returns the pixels still active. Cost: a few
  /// passes over the film's pixels.
  size_t after_pass(const Film& film, int samples_end);

  /// Whether pixel (x, y) (inside the film's crop window) takes the next pass's samples.
  bool active(int x, int y) const { return active_[index(x, y)] != 0; }
  size_t active_count() const { return active_count_; }
  /// The samples per pixel (x, y) received.
  int samples(int x, int y) const { return samples_[index(x, y)]; }
  /// Its relative standard error after the last pass (the 3×3 root mean square the decision used).
  float relative_error(int x, int y) const { return error_[index(x, y)]; }
  const AdaptiveSamplingSettings& settings() const { return settings_; }

 private:
  size_t index(int x, int y) const { return size_t(y - bounds_.y0) * size_t(bounds_.width()) + size_t(x - bounds_.x0); }
  double luminance_sum(const Film& film, int x, int y) const;
  void update_errors();

  PixelBounds bounds_;
  AdaptiveSamplingSettings settings_;
  bool camera_film_;
  int passes_ = 0, samples_end_ = 0;
  std::vector<double> last_luminance_, last_weight_;   ///< the film's sums after the previous pass
  std::vector<double> half_luminance_[2], half_weight_[2];
  std::vector<int> samples_;
  std::vector<float> error_;
  std::vector<uint8_t> active_;
  size_t active_count_;
};

}  // namespace rimu
