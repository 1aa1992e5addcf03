#include "render/interrupt_flag.h"

#include <atomic>
#include <cassert>
#include <csignal>

namespace rimu {
namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
std::atomic<bool> g_installed{false};
struct sigaction g_previous_int, g_previous_term;

extern "C" void on_sigint(int) { g_interrupted.store(true, std::memory_order_relaxed); }

}  // namespace

InterruptFlag::InterruptFlag() {
  [[maybe_unused]] const bool was_installed = g_installed.exchange(true);
  assert(!was_installed && "only one InterruptFlag may be alive at a time");
  g_interrupted.store(false);
  struct sigaction action = {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);  // what schedulers (Slurm, systemd) send before SIGKILL
}

InterruptFlag::~InterruptFlag() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
  g_installed.store(false);
}

bool InterruptFlag::requested() const { return g_interrupted.load(std::memory_order_relaxed); }

void InterruptFlag::request() { g_interrupted.store(true, std::memory_order_relaxed); }

}  // namespace rimu
