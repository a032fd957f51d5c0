#pragma once
// How far the running stage is, for `analyze`'s progress bar on a terminal.
// One per process: a stage with a long loop (reading, metrics, overlap,
// writing) announces its amount of work and adds to what is done as it goes;
// the terminal display polls it from its own thread. Nothing else reads it,
// so stages run the same with or without a display (batch runs several
// analyses at once and draws its own bar: the counts are then meaningless,
// and unread). Relaxed atomics: a stage pays one add per block of work.
// Each report of work (and each stage's start) is also where a stop request
// is honoured: these calls throw Interrupted or TimedOut (stop.h).

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

namespace hq::progress {

struct Snapshot {
  std::string stage;        // "" between stages
  std::uint64_t done = 0;   // work units done of total
  std::uint64_t total = 0;  // 0: the stage does not report its progress
};

// A stage begins (StageClock::start) or ends (StageClock::stop, stage "").
void stage_started(std::string stage);
// The running stage's amount of work (any unit), done reset to 0.
void set_total(std::uint64_t total);
void add_done(std::uint64_t amount);
void set_done(std::uint64_t done);
Snapshot snapshot();

// Whether a stage draws the bar, or only polls for stop requests because it
// runs beside another stage that owns the bar (the pipeline's metrics
// beside the overlap stage). The calls below do what add_done and set_total
// do when `reporting` is report; when silent, only the stop check.
enum class Reporting { report, silent };
void set_total(Reporting reporting, std::uint64_t total);
void add_done(Reporting reporting, std::uint64_t amount);

}  // namespace hq::progress
