#include "hqview/core/stop.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <string>
#include <thread>

#include "hqview/core/progress.h"

namespace HQ_TEST_UNIT {

struct ResetStop {
  ResetStop() { hq::stop::reset(); }
  ~ResetStop() { hq::stop::reset(); }
};

TEST(Stop, NothingRequestedChecksPass) {
  ResetStop reset;
  EXPECT_EQ(hq::stop::requested(), 0);
  EXPECT_NO_THROW(hq::stop::check());
  EXPECT_NO_THROW(hq::progress::add_done(1));
}

TEST(Stop, ASignalIsHonouredAtTheNextPollAndTheFirstOneWins) {
  ResetStop reset;
  hq::stop::request(SIGTERM);
  hq::stop::request(SIGINT);
  EXPECT_EQ(hq::stop::requested(), SIGTERM);
  try {
    hq::stop::check();
    FAIL() << "no Interrupted";
  } catch (const hq::Interrupted& e) {
    EXPECT_EQ(e.signal(), SIGTERM);
    EXPECT_STREQ(e.what(), "stopped by SIGTERM");
  }
  // Progress reports and stage starts are poll points; a stage's end is not
  // (StageClock's destructor calls it).
  EXPECT_THROW(hq::progress::add_done(1), hq::Interrupted);
  EXPECT_THROW(hq::progress::set_done(1), hq::Interrupted);
  // A stage that does not draw the bar still polls.
  EXPECT_THROW(hq::progress::add_done(hq::progress::Reporting::silent, 1), hq::Interrupted);
  EXPECT_THROW(hq::progress::stage_started("metrics"), hq::Interrupted);
  EXPECT_NO_THROW(hq::progress::stage_started(""));
}

// A silent stage leaves the running stage's counts as they are; a reporting
// one sets and adds to them.
TEST(Progress, ASilentStageLeavesTheBarAlone) {
  ResetStop reset;
  hq::progress::stage_started("overlap");
  hq::progress::set_total(5);
  hq::progress::add_done(2);
  hq::progress::set_total(hq::progress::Reporting::silent, 1000);
  hq::progress::add_done(hq::progress::Reporting::silent, 300);
  EXPECT_EQ(hq::progress::snapshot().total, 5u);
  EXPECT_EQ(hq::progress::snapshot().done, 2u);
  hq::progress::add_done(hq::progress::Reporting::report, 1);
  EXPECT_EQ(hq::progress::snapshot().done, 3u);
  hq::progress::set_total(hq::progress::Reporting::report, 7);
  EXPECT_EQ(hq::progress::snapshot().total, 7u);
  EXPECT_EQ(hq::progress::snapshot().done, 0u);
  hq::progress::stage_started("");
}

TEST(Stop, APollInsideAParallelLoopStopsTheLoopAndReachesTheCaller) {
  ResetStop reset;
  std::atomic<long> done{0};
  EXPECT_THROW(tbb::parallel_for(0L, 1L << 30, [&](long i) {
                 if (i == 1000) hq::stop::request(SIGINT);
                 done.fetch_add(1, std::memory_order_relaxed);
                 hq::stop::check();
               }),
               hq::Interrupted);
  EXPECT_LT(done.load(), 1L << 29);  // cancelled, not run to the end
}

TEST(Stop, ADeadlineBelongsToItsThreadAndEndsWithItsScope) {
  ResetStop reset;
  {
    hq::stop::ScopedDeadline deadline(0.05, "--mesh-timeout");
    EXPECT_NO_THROW(hq::stop::check());
    // Another thread has no deadline.
    std::thread other([] {
      std::this_thread::sleep_for(std::chrono::milliseconds(80));
      EXPECT_NO_THROW(hq::stop::check());
    });
    other.join();
    try {
      hq::stop::check();
      FAIL() << "no TimedOut";
    } catch (const hq::TimedOut& e) {
      EXPECT_STREQ(e.what(), "stopped after 0.05 s (--mesh-timeout)");
    }
  }
  EXPECT_NO_THROW(hq::stop::check());
}

TEST(Stop, NestedDeadlinesRestoreTheOuterOne) {
  ResetStop reset;
  hq::stop::ScopedDeadline outer(3600, "outer");
  {
    hq::stop::ScopedDeadline inner(0, "inner");
    EXPECT_THROW(hq::stop::check(), hq::TimedOut);
  }
  EXPECT_NO_THROW(hq::stop::check());
}

TEST(Stop, AThreadOfItsOwnCanTakeItsCallersDeadline) {
  // The UV atlas's thread (pipeline/analyze.cpp): the same deadline, the same
  // message; a caller without one hands none over.
  ResetStop reset;
  EXPECT_EQ(hq::stop::current_deadline(), nullptr);
  hq::stop::ScopedDeadline deadline(0.05, "--mesh-timeout 0.05");
  EXPECT_EQ(hq::stop::current_deadline(), &deadline);
  std::string message;
  std::thread worker([caller = hq::stop::current_deadline(), &message] {
    const hq::stop::ScopedDeadline same(caller);
    EXPECT_EQ(hq::stop::current_deadline(), &same);
    std::this_thread::sleep_for(std::chrono::milliseconds(80));
    try {
      hq::stop::check();
    } catch (const hq::TimedOut& e) {
      message = e.what();
    }
  });
  worker.join();
  EXPECT_EQ(message, "stopped after 0.05 s (--mesh-timeout 0.05)");
  std::thread without([] {
    const hq::stop::ScopedDeadline none(nullptr);
    EXPECT_EQ(hq::stop::current_deadline(), nullptr);
    EXPECT_NO_THROW(hq::stop::check());
  });
  without.join();
}

TEST(Stop, ACancelFlagStopsOnlyTheThreadThatWatchesIt) {
  ResetStop reset;
  std::atomic<bool> flag{false};
  std::atomic<bool> raised{false};
  bool cancelled = false;
  std::thread worker([&] {
    const hq::stop::ScopedCancel watch(flag);
    EXPECT_NO_THROW(hq::stop::check());
    raised = true;
    while (!flag) std::this_thread::yield();
    try {
      hq::stop::check();
    } catch (const hq::stop::Cancelled&) {
      cancelled = true;
    }
  });
  while (!raised) std::this_thread::yield();
  flag = true;
  worker.join();
  EXPECT_TRUE(cancelled);
  EXPECT_NO_THROW(hq::stop::check());  // this thread does not watch the flag
}

}  // namespace
