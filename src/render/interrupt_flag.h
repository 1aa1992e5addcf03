// Ctrl-C and SIGTERM as a request to stop: the render loop polls it, finishes the current pass and writes what it has.
#pragma once

namespace rimu {

/// While alive, SIGINT (Ctrl-C) and SIGTERM (what Slurm and other schedulers send before SIGKILL) set a flag instead
/// of killing the process. The handler is async-signal-safe: it only
/// stores to a lock-free std::atomic<bool>. It is installed with SA_RESETHAND, so the first signal of each kind also restores
/// its default action: a second Ctrl-C (or SIGTERM) kills the process at once (the way out if the render does not stop).
/// The destructor restores whatever handler was installed before. One instance at a time (asserted).
class InterruptFlag {
 public:
  InterruptFlag();
  ~InterruptFlag();
  InterruptFlag(const InterruptFlag&) = delete;
  InterruptFlag& operator=(const InterruptFlag&) = delete;

  /// True once SIGINT has arrived (or request() was called). Cheap: one relaxed atomic load; poll per tile.
  bool requested() const;
  /// Sets the flag as SIGINT would, without a signal (tests; a GUI's stop button).
  void request();
};

}  // namespace rimu
