#pragma once
// Stopping a run on request: a signal (SIGINT, SIGTERM) for the whole
// process, or a deadline for one mesh of a batch (--mesh-timeout). Nothing is
// interrupted from outside: the signal handler only records the signal, and
// the stages poll at their natural points (each stage's start and every block
// of work they report to progress.h), where check() throws. The exception
// unwinds through the bundle writer, which removes its temporary directory,
// so a stopped run leaves what was there before (docs/contract.md, "Exit
// codes"; ARCHITECTURE.md, "Faults").

#include <atomic>
#include <chrono>
#include <string>

#include "hqview/core/error.h"

namespace hq {

// The run was stopped by a signal; main exits 128 + signal().
class Interrupted : public Error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }

 private:
  int signal_;
};

// One mesh's analysis ran past its --mesh-timeout.
class TimedOut : public Error {
 public:
  using Error::Error;
};

namespace stop {

// Records a stop request. Async-signal-safe: the signal handler's only call.
void request(int signal) noexcept;
// The first signal requested, 0 if none.
int requested() noexcept;
// "SIGINT", "SIGTERM", "SIGHUP", else "signal N".
std::string signal_name(int signal);
// Forgets a request (tests; a library caller that handled it).
void reset() noexcept;

// Throws Interrupted when a stop was requested, TimedOut when the calling
// thread's deadline (ScopedDeadline) has passed, Cancelled when its
// ScopedCancel's flag is set; else returns at once (one relaxed load, plus
// a clock read when a deadline is set).
void check();

// Sets the calling thread's deadline while it lives: `seconds` from now,
// described in the TimedOut message as `what` ("--mesh-timeout 60").
// Work that the thread hands to other threads checks only the signal; the
// calling thread polls its own share, so a long parallel stage still stops
// (batch runs each mesh in an isolated TBB region so that a thread never
// checks one mesh's deadline inside another mesh's work).
class ScopedDeadline {
 public:
  ScopedDeadline(double seconds, const char* what);
  // The deadline another thread set (`same_as`, from current() there) on
  // this thread too, for work handed to a thread of its own; none if null.
  explicit ScopedDeadline(const ScopedDeadline* same_as);
  ScopedDeadline(const ScopedDeadline&) = delete;
  ScopedDeadline& operator=(const ScopedDeadline&) = delete;
  ~ScopedDeadline();

  std::chrono::steady_clock::time_point at;
  double seconds;
  const char* what;

 private:
  const ScopedDeadline* previous_;
};

// The calling thread's innermost deadline, null if none.
const ScopedDeadline* current_deadline() noexcept;

// Work handed to a thread of its own that its owner may abandon (the
// pipeline's UV atlas when a stage beside it fails): while a ScopedCancel
// lives on that thread, check() there throws Cancelled once `flag` is set.
// Cancelled never reaches the user: the owner raises the flag only when it
// will not read the work's result.
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
};
class ScopedCancel {
 public:
  explicit ScopedCancel(const std::atomic<bool>& flag);
  ScopedCancel(const ScopedCancel&) = delete;
  ScopedCancel& operator=(const ScopedCancel&) = delete;
  ~ScopedCancel();

 private:
  const std::atomic<bool>* previous_;
};

}  // namespace stop
}  // namespace hq
