#include "hqview/core/stop.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <string>

namespace hq {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

struct Deadline {
  std::chrono::steady_clock::time_point at;
  double seconds;
  const char* what;
};
thread_local const Deadline* t_deadline = nullptr;

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "signal " + std::to_string(signal);
  }
}

}  // namespace

Interrupted::Interrupted(int signal) : Error("stopped by " + signal_name(signal)), signal_(signal) {}

namespace stop {

void request(int signal) noexcept {
  int expected = 0;
  g_signal.compare_exchange_strong(expected, signal, std::memory_order_relaxed);
}

int requested() noexcept { return g_signal.load(std::memory_order_relaxed); }

void reset() noexcept { g_signal.store(0, std::memory_order_relaxed); }

void check() {
  if (const int s = requested(); s != 0) throw Interrupted(s);
  if (const Deadline* d = t_deadline; d != nullptr && std::chrono::steady_clock::now() >= d->at) {
    std::string seconds = std::to_string(d->seconds);
    seconds.erase(seconds.find_last_not_of('0') + 1);
    if (!seconds.empty() && seconds.back() == '.') seconds.pop_back();
    throw TimedOut("stopped after " + seconds + " s (" + d->what + ")");
  }
}

ScopedDeadline::ScopedDeadline(double seconds, const char* what) : previous_(t_deadline) {
  const auto span = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds));
  t_deadline = new Deadline{std::chrono::steady_clock::now() + span, seconds, what};
}

ScopedDeadline::~ScopedDeadline() {
  delete t_deadline;
  t_deadline = static_cast<const Deadline*>(previous_);
}

}  // namespace stop
}  // namespace hq
