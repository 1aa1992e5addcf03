// A progress line for long renders: percentage, samples per second and time left.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace rimu {

/// Reports progress of `total` units of work (camera samples) on a stream, from any number of threads.
///
/// On a terminal it redraws one line with carriage returns, at most once per `min_interval_s` (0.25 s: ~4/s, fast
/// enough to look live, slow enough to cost nothing). When the stream is not a terminal (a log, a pipe, CI) it
/// writes a render log: one line each time the work crosses a multiple of `log_step_percent` (10 %: ten lines per
/// render) with the samples per second, the time elapsed and the time left, and the final line from finish().
/// add() is lock-free except for the thread that happens to draw (other threads never wait for a redraw).
///
/// A render to a time budget (`time_budget_s` > 0) has no known sample total: its fraction done is the larger of
/// the samples' and the budget's (render time, `time_spent_s` of it before this run), so the log lines step
/// through the budget, and its time left is the budget's.
class ProgressReporter {
 public:
  struct Options {
    std::FILE* stream = stderr;
    int terminal = -1;            ///< 1 / 0 force terminal mode on / off; -1 asks isatty() on the stream
    double min_interval_s = 0.25;
    bool silent = false;          ///< print nothing at all, not even the final line (rimu --quiet)
    double log_step_percent = 10.0;  ///< off a terminal: one line per this much progress
    double time_budget_s = 0.0;      ///< > 0: a time budget (see above)
    double time_spent_s = 0.0;       ///< of the budget, before this run (a resumed render)
  };

  ProgressReporter(uint64_t total, std::string label, Options options);
  ProgressReporter(uint64_t total, std::string label) : ProgressReporter(total, std::move(label), Options{}) {}
  /// Calls finish() if nobody did.
  ~ProgressReporter();

  /// Records `units` more units done (thread-safe).
  void add(uint64_t units);
  /// Prints the final line (total time and rate; "interrupted" if not all work was done). Idempotent.
  void finish();
  /// The work ended complete with less than `total` done (a time budget was spent): finish() says 100 %.
  void mark_complete();

  uint64_t done() const { return done_.load(std::memory_order_relaxed); }
  bool terminal() const { return terminal_; }
  /// Number of lines/redraws written so far (tests).
  int redraw_count() const { return redraws_; }

  /// "1:02:03" / "2:03" formatting of a duration in seconds.
  static std::string format_duration(double seconds);

 private:
  void draw(bool final_line);
  double elapsed_s() const;
  /// The fraction of the work done (samples or time budget) after `elapsed` seconds, in [0, 1].
  double fraction_done(uint64_t done, double elapsed) const;
  /// Seconds left after `elapsed` at `rate` units/s (NaN if unknown).
  double seconds_left(uint64_t done, double elapsed, double rate) const;

  uint64_t total_;
  std::string label_;
  Options options_;
  bool terminal_;
  std::atomic<uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::atomic<int64_t> next_draw_ns_{0};
  std::atomic<int> logged_steps_{0};  ///< off a terminal: the progress steps already logged
  std::mutex draw_mutex_;
  int redraws_ = 0;
  bool finished_ = false;
  bool complete_ = false;  ///< mark_complete(): ended on its budget
};

}  // namespace rimu
