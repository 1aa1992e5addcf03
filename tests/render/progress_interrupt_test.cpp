// The progress line (terminal and quiet modes) and Ctrl-C handling.
#include <doctest/doctest.h>

#include <csignal>
#include <cstdio>
#include <string>

#include "render/interrupt_flag.h"
#include "render/progress_reporter.h"

using namespace rimu;

namespace {

std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string out;
  char buffer[512];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0) out.append(buffer, n);
  return out;
}

volatile std::sig_atomic_t g_previous_handler_calls = 0;
extern "C" void previous_handler(int) { g_previous_handler_calls = g_previous_handler_calls + 1; }

}  // namespace

TEST_CASE("progress: off a terminal, a render log of one line per 10 % and the final line") {
  std::FILE* f = std::tmpfile();
  {
    ProgressReporter progress(1000, "Rendering", {f, 0, 0.0});
    CHECK_FALSE(progress.terminal());
    for (int i = 0; i < 100; ++i) progress.add(10);
    CHECK(progress.redraw_count() == 9);  // 10 % … 90 %; 100 % is the final line
    progress.finish();
    progress.finish();  // idempotent
    CHECK(progress.redraw_count() == 10);
  }
  const std::string text = contents(f);
  CHECK(text.find("Rendering: 10.0%, ") == 0);
  CHECK(text.find("samples/s, ") != std::string::npos);
  CHECK(text.find(" elapsed, ") != std::string::npos);
  CHECK(text.find(" left\n") != std::string::npos);
  CHECK(text.find("Rendering: 90.0%, ") != std::string::npos);
  CHECK(text.find("Rendering: 100.0% in") != std::string::npos);
  CHECK(text.find('\r') == std::string::npos);
  CHECK(text.back() == '\n');
  std::fclose(f);
}

TEST_CASE("progress: a big step logs once, however many adds cross it, and --quiet logs nothing") {
  std::FILE* f = std::tmpfile();
  {
    ProgressReporter progress(1000, "Rendering", {f, 0, 0.0});
    progress.add(350);  // 35 %: one line, not three
    CHECK(progress.redraw_count() == 1);
    progress.add(10);   // still in the 30 % step
    CHECK(progress.redraw_count() == 1);
    ProgressReporter::Options quiet{f, 0, 0.0};
    quiet.silent = true;
    ProgressReporter silent(1000, "Silent", quiet);
    for (int i = 0; i < 10; ++i) silent.add(100);
    CHECK(silent.redraw_count() == 0);
  }
  CHECK(contents(f).find("Silent") == std::string::npos);
  std::fclose(f);
}

TEST_CASE("progress: a time budget counts time, and a render that spent it finishes at 100 %") {
  std::FILE* f = std::tmpfile();
  {
    ProgressReporter::Options options{f, 0, 0.0};
    options.time_budget_s = 1e6;  // far away: the fraction is the samples'
    options.time_spent_s = 0.5e6;  // half of it spent before: 50 % at once
    ProgressReporter progress(1000, "Rendering", options);
    progress.add(1);
    CHECK(progress.redraw_count() == 1);
    progress.mark_complete();
  }
  const std::string text = contents(f);
  CHECK(text.find("Rendering: 50.0%, ") == 0);
  CHECK(text.find("Rendering: 100.0% in") != std::string::npos);
  CHECK(text.find("interrupted") == std::string::npos);
  std::fclose(f);
}

TEST_CASE("progress: a terminal gets carriage-return redraws, rate-limited") {
  std::FILE* f = std::tmpfile();
  {
    // A 1 h interval: only the first add() may draw, however many follow.
    ProgressReporter progress(400, "Rendering", {f, 1, 3600.0});
    for (int i = 0; i < 100; ++i) progress.add(2);
    CHECK(progress.redraw_count() == 1);
    CHECK(progress.done() == 200);
  }  // the destructor prints the final line: half done, so "interrupted at"
  const std::string text = contents(f);
  CHECK(text.rfind("\rRendering [", 0) == 0);
  CHECK(text.find("ETA") != std::string::npos);
  CHECK(text.find("interrupted at 50.0%") != std::string::npos);
  CHECK(ProgressReporter::format_duration(3725.0) == "1:02:05");
  CHECK(ProgressReporter::format_duration(65.0) == "1:05");
  std::fclose(f);
}

TEST_CASE("InterruptFlag: SIGINT sets the flag, the next one gets the default action, the old handler returns") {
  struct sigaction custom = {}, query = {};
  custom.sa_handler = previous_handler;
  sigemptyset(&custom.sa_mask);
  sigaction(SIGINT, &custom, nullptr);
  {
    InterruptFlag flag;
    CHECK_FALSE(flag.requested());
    std::raise(SIGINT);
    CHECK(flag.requested());
    CHECK(g_previous_handler_calls == 0);
    // SA_RESETHAND: the handler is gone after the first Ctrl-C, so a second one would kill the process.
    sigaction(SIGINT, nullptr, &query);
    CHECK((query.sa_handler == SIG_DFL));
  }
  sigaction(SIGINT, nullptr, &query);
  CHECK((query.sa_handler == previous_handler));
  {
    InterruptFlag flag;  // a new flag starts clear
    CHECK_FALSE(flag.requested());
    flag.request();
    CHECK(flag.requested());
  }
  signal(SIGINT, SIG_DFL);
}
