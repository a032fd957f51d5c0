#include "hqview/core/progress.h"

#include <utility>

#include "hqview/core/stop.h"

namespace hq::progress {
namespace {

struct State {
  std::mutex mutex;  // guards stage
  std::string stage;
  std::atomic<std::uint64_t> done{0};
  std::atomic<std::uint64_t> total{0};
};

State& state() {
  static State s;
  return s;
}

}  // namespace

void stage_started(std::string stage) {
  // A stage's start is a point where a stop request is honoured; its end
  // ("", from StageClock's destructor among others) is not: it must not throw.
  if (!stage.empty()) stop::check();
  State& s = state();
  const std::lock_guard lock(s.mutex);
  s.stage = std::move(stage);
  s.total.store(0, std::memory_order_relaxed);
  s.done.store(0, std::memory_order_relaxed);
}

void set_total(std::uint64_t total) {
  state().done.store(0, std::memory_order_relaxed);
  state().total.store(total, std::memory_order_relaxed);
}

void add_done(std::uint64_t amount) {
  state().done.fetch_add(amount, std::memory_order_relaxed);
  stop::check();
}

void set_done(std::uint64_t done) {
  state().done.store(done, std::memory_order_relaxed);
  stop::check();
}

void set_total(Reporting reporting, std::uint64_t total) {
  if (reporting == Reporting::report) set_total(total);
}

void add_done(Reporting reporting, std::uint64_t amount) {
  if (reporting == Reporting::report)
    add_done(amount);
  else
    stop::check();
}

Snapshot snapshot() {
  State& s = state();
  Snapshot out;
  {
    const std::lock_guard lock(s.mutex);
    out.stage = s.stage;
  }
  out.done = s.done.load(std::memory_order_relaxed);
  out.total = s.total.load(std::memory_order_relaxed);
  return out;
}

}  // namespace hq::progress
