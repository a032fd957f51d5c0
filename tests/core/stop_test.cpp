#include "hqview/core/stop.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <string>
#include <thread>

#include "hqview/core/progress.h"

namespace {

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
  EXPECT_THROW(hq::progress::stage_started("metrics"), hq::Interrupted);
  EXPECT_NO_THROW(hq::progress::stage_started(""));
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

}  // namespace
