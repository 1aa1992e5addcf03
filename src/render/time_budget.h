// A render to a time budget (`rimu --time 90s`, the scene's "integrator": {"time_limit_s": …}): whole passes
// until the budget is spent.
#pragma once

namespace rimu {

/// Decides before each pass of the render loop (renderer.h) whether that pass still fits the budget.
///
/// Passes are never cut: the film only ever holds whole passes, so a render that stops on its budget is the same
/// image, bit for bit, as a fixed-spp render of the samples it reached (and --resume continues it exactly).
/// A pass is started when the render has no samples yet (an image needs one pass, however small the budget), or
/// when the time spent plus the predicted time of the pass fits the budget. The prediction is the time per sample
/// of the pass before it in this run times the pass's samples; with no pass timed yet (the first of a resumed
/// render) a pass starts if any budget is left. So a render ends within one pass of its budget and, once a pass
/// has been timed, at most one pass's misprediction past it.
class TimeBudget {
 public:
  /// `limit_s` > 0: the whole render's budget of render time. `spent_s`: what a resumed render already spent.
  TimeBudget(double limit_s, double spent_s) : limit_s_(limit_s), spent_s_(spent_s) {}

  /// Called before each pass, `elapsed_s` after this run started, for a pass of `pass_samples` samples per pixel
  /// (a mean over the pixels when they take unequal counts, as in adaptive sampling); `film_empty`: nothing
  /// rendered yet. True: render it. Each call is taken to start the pass it allows.
  bool allows_pass(double elapsed_s, double pass_samples, bool film_empty);

  double limit_s() const { return limit_s_; }
  /// True once a pass was refused: the render ended on its budget.
  bool spent() const { return spent_; }

 private:
  double limit_s_, spent_s_;
  double pass_start_s_ = -1.0;  ///< when the last allowed pass started (−1: none yet)
  double pass_samples_ = 0;     ///< its samples per pixel
  bool spent_ = false;
};

}  // namespace rimu
