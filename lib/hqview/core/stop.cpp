#include "hqview/core/stop.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <string>

#include "hqview/core/number_format.h"

namespace hq {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

thread_local const stop::ScopedDeadline* t_deadline = nullptr;
thread_local const std::atomic<bool>* t_cancel = nullptr;

}  // namespace

Interrupted::Interrupted(int signal) : Error("stopped by " + stop::signal_name(signal)), signal_(signal) {}

namespace stop {

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "signal " + std::to_string(signal);
  }
}

void request(int signal) noexcept {
  int expected = 0;
  g_signal.compare_exchange_strong(expected, signal, std::memory_order_relaxed);
}

int requested() noexcept { return g_signal.load(std::memory_order_relaxed); }

void reset() noexcept { g_signal.store(0, std::memory_order_relaxed); }

void check() {
  if (const int s = requested(); s != 0) throw Interrupted(s);
  if (const stop::ScopedDeadline* d = t_deadline; d != nullptr && std::chrono::steady_clock::now() >= d->at)
    throw TimedOut("stopped after " + format_double(d->seconds) + " s (" + d->what + ")");
  if (const std::atomic<bool>* c = t_cancel; c != nullptr && c->load(std::memory_order_relaxed)) throw Cancelled();
}

ScopedDeadline::ScopedDeadline(double seconds_, const char* what_)
    : at(std::chrono::steady_clock::now() +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds_))),
      seconds(seconds_),
      what(what_),
      previous_(t_deadline) {
  t_deadline = this;
}

ScopedDeadline::ScopedDeadline(const ScopedDeadline* same_as)
    : at(same_as ? same_as->at : std::chrono::steady_clock::time_point::max()),
      seconds(same_as ? same_as->seconds : 0.0),
      what(same_as ? same_as->what : ""),
      previous_(t_deadline) {
  if (same_as) t_deadline = this;
}

ScopedDeadline::~ScopedDeadline() { t_deadline = previous_; }

const ScopedDeadline* current_deadline() noexcept { return t_deadline; }

ScopedCancel::ScopedCancel(const std::atomic<bool>& flag) : previous_(t_cancel) { t_cancel = &flag; }

ScopedCancel::~ScopedCancel() { t_cancel = previous_; }

}  // namespace stop
}  // namespace hq
