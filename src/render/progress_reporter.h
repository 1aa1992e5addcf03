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
/// enough to look live, slow enough to cost nothing); when the stream is not a terminal (a log, a pipe, CI) it
/// stays quiet and prints one final line from finish(). add() is lock-free except for the thread that happens to
/// redraw (try_lock: other threads never wait).
class ProgressReporter {
 public:
  struct Options {
    std::FILE* stream = stderr;
    int terminal = -1;            ///< 1 / 0 force terminal mode on / off; -1 asks isatty() on the stream
    double min_interval_s = 0.25;
    bool silent = false;          ///< print nothing at all, not even the final line (rimu --quiet)
  };

  ProgressReporter(uint64_t total, std::string label, Options options);
  ProgressReporter(uint64_t total, std::string label) : ProgressReporter(total, std::move(label), Options{}) {}
  /// Calls finish() if nobody did.
  ~ProgressReporter();

  /// Records `units` more units done (thread-safe).
  void add(uint64_t units);
  /// Prints the final line (total time and rate; "interrupted" if not all work was done). Idempotent.
  void finish();

  uint64_t done() const { return done_.load(std::memory_order_relaxed); }
  bool terminal() const { return terminal_; }
  /// Number of lines/redraws written so far (tests).
  int redraw_count() const { return redraws_; }

  /// "1:02:03" / "2:03" formatting of a duration in seconds.
  static std::string format_duration(double seconds);

 private:
  void draw(bool final_line);
  double elapsed_s() const;

  uint64_t total_;
  std::string label_;
  Options options_;
  bool terminal_;
  std::atomic<uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::atomic<int64_t> next_draw_ns_{0};
  std::mutex draw_mutex_;
  int redraws_ = 0;
  bool finished_ = false;
};

}  // namespace rimu
