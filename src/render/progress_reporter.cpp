#include "render/progress_reporter.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace rimu {

ProgressReporter::ProgressReporter(uint64_t total, std::string label, Options options)
    : total_(total),
      label_(std::move(label)),
      options_(options),
      terminal_(!options.silent &&
                (options.terminal >= 0 ? options.terminal == 1 : ::isatty(::fileno(options.stream)) == 1)),
      start_(std::chrono::steady_clock::now()) {}

ProgressReporter::~ProgressReporter() { finish(); }

double ProgressReporter::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string ProgressReporter::format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long s = std::lround(seconds);
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(text, sizeof(text), "%ld:%02ld", s / 60, s % 60);
  return text;
}

double ProgressReporter::fraction_done(uint64_t done, double elapsed) const {
  double fraction = total_ > 0 ? double(std::min(done, total_)) / double(total_) : 1.0;
  if (options_.time_budget_s > 0)
    fraction = std::max(fraction, (options_.time_spent_s + elapsed) / options_.time_budget_s);
  return std::min(fraction, 1.0);
}

double ProgressReporter::seconds_left(uint64_t done, double elapsed, double rate) const {
  const double by_samples = rate > 0 ? double(total_ - std::min(done, total_)) / rate : NAN;
  if (!(options_.time_budget_s > 0)) return by_samples;
  const double by_budget = std::max(0.0, options_.time_budget_s - options_.time_spent_s - elapsed);
  return std::isnan(by_samples) ? by_budget : std::min(by_samples, by_budget);
}

void ProgressReporter::add(uint64_t units) {
  const uint64_t done = done_.fetch_add(units, std::memory_order_relaxed) + units;
  if (options_.silent) return;
  if (!terminal_) {
    // A render log: one line per step crossed; the thread that crosses it claims it, the others carry on.
    if (!(options_.log_step_percent > 0)) return;
    const int step = int(std::floor(100.0 * fraction_done(done, elapsed_s()) / options_.log_step_percent));
    if (double(step) * options_.log_step_percent >= 100.0) return;  // the final line says 100 %
    int logged = logged_steps_.load(std::memory_order_relaxed);
    if (step <= logged || !logged_steps_.compare_exchange_strong(logged, step)) return;
    std::lock_guard lock(draw_mutex_);
    if (!finished_) draw(false);
    return;
  }
  const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::steady_clock::now() - start_).count();
  int64_t due = next_draw_ns_.load(std::memory_order_relaxed);
  if (now_ns < due) return;
  // One thread claims this redraw; the others carry on rendering.
  if (!next_draw_ns_.compare_exchange_strong(due, now_ns + int64_t(options_.min_interval_s * 1e9))) return;
  std::unique_lock lock(draw_mutex_, std::try_to_lock);
  if (lock.owns_lock() && !finished_) draw(false);
}

void ProgressReporter::mark_complete() {
  std::lock_guard lock(draw_mutex_);
  complete_ = true;
}

void ProgressReporter::draw(bool final_line) {
  const uint64_t done = done_.load(std::memory_order_relaxed);
  const double elapsed = elapsed_s();
  const double fraction = complete_ ? 1.0 : fraction_done(done, elapsed);
  const double rate = elapsed > 0 ? double(done) / elapsed : 0.0;
  char line[256];
  if (final_line) {
    std::snprintf(line, sizeof(line), "%s: %s%.1f%% in %s, %.3g samples/s", label_.c_str(),
                  fraction < 1.0 ? "interrupted at " : "", 100.0 * fraction, format_duration(elapsed).c_str(), rate);
  } else if (!terminal_) {
    std::snprintf(line, sizeof(line), "%s: %.1f%%, %.3g samples/s, %s elapsed, %s left", label_.c_str(),
                  100.0 * fraction, rate, format_duration(elapsed).c_str(),
                  format_duration(seconds_left(done, elapsed, rate)).c_str());
  } else {
    constexpr int kBarWidth = 30;
    char bar[kBarWidth + 1];
    const int filled = int(fraction * kBarWidth);
    for (int i = 0; i < kBarWidth; ++i) bar[i] = i < filled ? '=' : ' ';
    bar[kBarWidth] = '\0';
    std::snprintf(line, sizeof(line), "%s [%s] %5.1f%% %.3g samples/s ETA %s", label_.c_str(), bar,
                  100.0 * fraction, rate, format_duration(seconds_left(done, elapsed, rate)).c_str());
  }
  // "\r...\033[K": back to the line start, write, clear what a longer previous line left behind.
  if (terminal_)
    std::fprintf(options_.stream, "\r%s\033[K%s", line, final_line ? "\n" : "");
  else
    std::fprintf(options_.stream, "%s\n", line);
  std::fflush(options_.stream);
  ++redraws_;
}

void ProgressReporter::finish() {
  std::lock_guard lock(draw_mutex_);
  if (finished_) return;
  if (!options_.silent) draw(true);
  finished_ = true;
}

}  // namespace rimu
