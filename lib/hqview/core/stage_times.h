#pragma once
// Wall times of named stages, for OUT/timings.json and `--verbose`:
// measured, so never part of report.json (which stays byte-identical from
// run to run). A StageClock times consecutive stages: start() ends the
// running stage and begins the next, stop() ends it; each finished stage is
// appended to the list and handed to the sink (main prints it).

#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "hqview/core/progress.h"

namespace hq {

struct StageTime {
  std::string name;
  double seconds = 0.0;
  std::uint64_t peak_rss_bytes = 0;  // the process's peak resident memory when the stage ended
  // Ran on its own thread beside the stages listed around it (the UV atlas):
  // not part of the sum that accounts for the wall time.
  bool concurrent = false;
};

// The process's peak resident set so far (getrusage), in bytes.
inline std::uint64_t peak_rss_bytes() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux: KiB
}

using StageSink = std::function<void(const StageTime&)>;

class StageClock {
 public:
  StageClock(std::vector<StageTime>& out, StageSink sink) : out_(out), sink_(std::move(sink)) {}
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;
  ~StageClock() { stop(); }

  void start(std::string name) {
    stop();
    name_ = std::move(name);
    progress::stage_started(name_);
    begin_ = std::chrono::steady_clock::now();
    running_ = true;
  }
  // A stage timed elsewhere (a view drawn on a second thread): appended and
  // handed to the sink like the others; `concurrent` as in StageTime.
  void record(std::string name, double seconds, bool concurrent) {
    out_.push_back({std::move(name), seconds, peak_rss_bytes(), concurrent});
    if (sink_) sink_(out_.back());
  }
  void stop() {
    if (!running_) return;
    running_ = false;
    progress::stage_started("");
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - begin_;
    out_.push_back({std::move(name_), elapsed.count(), peak_rss_bytes()});
    if (sink_) sink_(out_.back());
  }

 private:
  std::vector<StageTime>& out_;
  StageSink sink_;
  std::string name_;
  std::chrono::steady_clock::time_point begin_{};
  bool running_ = false;
};

}  // namespace hq
