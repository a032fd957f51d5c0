#include "hqview/quality/statistics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <tbb/global_control.h>

#include "hqview/quality/corner_jacobian.h"

namespace hq {
namespace HQ_TEST_UNIT {

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
  const Statistics s = compute_statistics(
      std::vector<double>{}, StatisticsOptions{.histogram_min = {}, .histogram_max = {}, .histogram_bins = 3});
  EXPECT_EQ(s.count, 0);
  EXPECT_EQ(s.histogram.counts, (std::vector<std::int64_t>{0, 0, 0}));
}

}  // namespace
}  // namespace hq

namespace hq {
namespace HQ_TEST_UNIT {

// The reference: the definitions as written (kept values copied, one
// std::sort, ascending sums, numpy's linear percentiles).
Statistics reference_statistics(const std::vector<double>& values) {
  std::vector<double> kept;
  for (double v : values)
    if (!std::isnan(v) && std::abs(v) < kVerdictDegenerate) kept.push_back(v);
  std::sort(kept.begin(), kept.end());
  Statistics s;
  s.count = static_cast<std::int64_t>(kept.size());
  double sum = 0;
  for (double v : kept) sum += v;
  s.mean = sum / static_cast<double>(kept.size());
  double squares = 0;
  for (double v : kept) squares += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(squares / static_cast<double>(kept.size()));
  s.min = kept.front();
  s.max = kept.back();
  s.p01 = percentile_of_sorted(kept, 0.01);
  s.p50 = percentile_of_sorted(kept, 0.50);
  s.p99 = percentile_of_sorted(kept, 0.99);
  // The histogram over [min, max], 20 bins, value by value.
  s.histogram.counts.assign(20, 0);
  for (double v : kept) {
    const double t = (v - s.min) / (s.max - s.min) * 20;
    ++s.histogram.counts[static_cast<std::size_t>(std::clamp(static_cast<int>(std::floor(t)), 0, 19))];
  }
  return s;
}

TEST(Statistics, BucketedOrderEqualsOneSortBitForBit) {
  // Shapes that stress the bucketing: a narrow range (every value shares
  // its high bits), a range over many orders of magnitude with both signs,
  // a handful of distinct values repeated (one bucket holds most), and
  // zeros of both signs; sentinels and NaN mixed in.
  std::mt19937_64 rng(20);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<double>> cases(4);
  for (int i = 0; i < 200000; ++i) {
    cases[0].push_back(0.9 + 1e-9 * unit(rng));
    cases[1].push_back((unit(rng) < 0.5 ? -1 : 1) * std::pow(10.0, -300 + 330 * unit(rng)));
    cases[2].push_back(std::array<double, 4>{1.0, 0.5, -0.25, 1.0}[static_cast<std::size_t>(i) % 4]);
    cases[3].push_back(i % 3 == 0 ? 0.0 : i % 3 == 1 ? -0.0 : unit(rng) - 0.5);
  }
  for (auto& c : cases) {
    c.push_back(kVerdictDegenerate);
    c.push_back(-kVerdictDegenerate);
    c.push_back(std::numeric_limits<double>::quiet_NaN());
  }
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Statistics got = compute_statistics(cases[k]), want = reference_statistics(cases[k]);
    EXPECT_EQ(got.count, want.count) << k;
    EXPECT_EQ(got.num_degenerate, 2) << k;
    EXPECT_EQ(got.histogram.counts, want.histogram.counts) << k;
    for (const auto& [a, b] : {std::pair{got.mean, want.mean},
                               {got.std, want.std},
                               {got.min, want.min},
                               {got.max, want.max},
                               {got.p01, want.p01},
                               {got.p50, want.p50},
                               {got.p99, want.p99}})
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a == 0.0 ? 0.0 : a), std::bit_cast<std::uint64_t>(b == 0.0 ? 0.0 : b))
          << "case " << k << ": " << a << " vs " << b;
  }
}


TEST(Statistics, ParallelBucketSortsEqualOneSortForAnyThreadCount) {
  // Over 2^20 kept values: the buckets are sorted in parallel. Corner-like
  // values (most in [0.6, 1], a few negative, a run of equal ones, zeros of
  // both signs): every number bit for bit the definition's, with 1 and 2
  // threads.
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> v(1'200'000);
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = i % 5000 == 0 ? -0.9 * unit(rng) : i % 7 == 0 ? 1.0 : i % 11 == 0 ? (i % 2 ? 0.0 : -0.0)
                                                              : 1.0 - 0.4 * unit(rng) * unit(rng);
  // Left out wherever they fall in the slices that are counted at once.
  for (std::size_t i = 0; i < v.size(); i += 100'003) v[i] = i % 2 ? kVerdictDegenerate : -kVerdictDegenerate;
  v[777'777] = std::numeric_limits<double>::quiet_NaN();
  const Statistics want = reference_statistics(v);
  for (const std::size_t threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const Statistics got = compute_statistics(v);
    EXPECT_EQ(got.count, want.count);
    EXPECT_EQ(got.num_degenerate, 12);
    EXPECT_EQ(got.histogram.counts, want.histogram.counts);
    for (const auto& [a, b] : {std::pair{got.mean, want.mean}, {got.std, want.std}, {got.min, want.min},
                               {got.max, want.max}, {got.p01, want.p01}, {got.p50, want.p50}, {got.p99, want.p99}})
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b)) << threads << " threads";
  }
}

}  // namespace
}  // namespace hq
