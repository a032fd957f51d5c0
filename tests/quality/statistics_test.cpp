#include "hqview/quality/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hq {
namespace {

TEST(Statistics, HandComputedSmallSet) {
  const std::vector<double> v = {0.5, -0.25, 1.0, 0.0, 0.75};
  const Statistics s = compute_statistics(v, {.histogram_min = -1.0, .histogram_max = 1.0, .histogram_bins = 4});
  EXPECT_EQ(s.count, 5);
  EXPECT_EQ(s.min, -0.25);
  EXPECT_EQ(s.max, 1.0);
  EXPECT_DOUBLE_EQ(s.mean, 0.4);
  // Deviations from 0.4: 0.1, -0.65, 0.6, -0.4, 0.35 -> squares sum 1.075.
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.075 / 5));
  EXPECT_DOUBLE_EQ(s.p50, 0.5);
  // numpy.percentile([-.25,0,.5,.75,1], 5) = -0.25 + 0.2*0.25 = -0.2
  EXPECT_DOUBLE_EQ(s.p05, -0.2);
  EXPECT_DOUBLE_EQ(s.p95, 0.95);
  EXPECT_EQ(s.num_inverted, 2);  // -0.25 and 0.0
  EXPECT_EQ(s.histogram.edges, (std::vector<double>{-1.0, -0.5, 0.0, 0.5, 1.0}));
  // Bins [-1,-.5) [-.5,0) [0,.5) [.5,1]: -0.25 | 0.0 | 0.5 0.75 1.0
  EXPECT_EQ(s.histogram.counts, (std::vector<std::int64_t>{0, 1, 1, 3}));
}

TEST(Statistics, DegenerateSentinelsAndNaNAreKeptOut) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> v = {1e30, 0.2, nan, 0.4, -1e30};
  const Statistics s = compute_statistics(v);
  EXPECT_EQ(s.count, 2);
  EXPECT_EQ(s.num_degenerate, 2);
  EXPECT_DOUBLE_EQ(s.mean, 0.30000000000000004);
  EXPECT_EQ(s.max, 0.4);
  EXPECT_EQ(s.min, 0.2);
}

TEST(Statistics, FlaggedEntriesAreDegenerate) {
  const std::vector<double> v = {0.0, 0.5, 0.0};
  const std::vector<std::uint8_t> flags = {1, 0, 0};
  const Statistics s = compute_statistics(v, {}, flags);
  EXPECT_EQ(s.count, 2);
  EXPECT_EQ(s.num_degenerate, 1);
  EXPECT_EQ(s.num_inverted, 1);
}

TEST(Statistics, OrderDoesNotChangeTheBytes) {
  std::vector<double> v;
  for (int i = 0; i < 1000; ++i) v.push_back(std::sin(i * 0.37) * 1e-3 + i * 1e-7);
  const Statistics a = compute_statistics(v);
  std::reverse(v.begin(), v.end());
  const Statistics b = compute_statistics(v);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.std, b.std);
  EXPECT_EQ(a.histogram.counts, b.histogram.counts);
}

TEST(Statistics, EmptyInput) {
  const Statistics s = compute_statistics(std::vector<double>{}, StatisticsOptions{.histogram_min = {}, .histogram_max = {}, .histogram_bins = 3});
  EXPECT_EQ(s.count, 0);
  EXPECT_EQ(s.histogram.counts, (std::vector<std::int64_t>{0, 0, 0}));
}

}  // namespace
}  // namespace hq
