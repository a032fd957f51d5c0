#pragma once
// Summary statistics of a per-element field, as report.json writes them
// (CONTRACT.md `...stats`): count, min, max, mean, std, percentiles and a
// histogram. Deterministic: sums and percentiles taken sequentially on the
// values in ascending order (sorted by buckets, in parallel on large inputs:
// the order, hence every number, is the same for any thread count).

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "hqview/core/types.h"

namespace hq {

struct Histogram {
  std::vector<double> edges;          // bins + 1 ascending edges
  std::vector<std::int64_t> counts;   // bins
};

struct Statistics {
  std::int64_t count = 0;  // values that entered the statistics
  double min = 0, max = 0, mean = 0, std = 0;
  double p01 = 0, p05 = 0, p50 = 0, p95 = 0, p99 = 0;
  std::int64_t num_inverted = 0;    // values <= 0 (for Jacobian-type fields)
  std::int64_t num_degenerate = 0;  // excluded: Verdict's 1e30 sentinels or flagged entries
  Histogram histogram;
};

struct StatisticsOptions {
  // Histogram range; when unset, [min, max] of the values.
  std::optional<double> histogram_min;
  std::optional<double> histogram_max;
  int histogram_bins = 20;
};

// Statistics of `values`. NaN entries are ignored (not counted anywhere);
// entries with |v| >= 1e30 or with degenerate[i] != 0 (when `degenerate` is
// not empty) are counted in num_degenerate and left out of everything else.
// Percentiles interpolate linearly between closest ranks (numpy's default).
// std is the population standard deviation. With no counted value every
// number is 0 and the histogram counts are all 0.
Statistics compute_statistics(std::span<const double> values, const StatisticsOptions& options = {},
                              std::span<const std::uint8_t> degenerate = {});

// The same numbers, the ascending copy of the kept values made in `buffer`
// (resized; its memory reused by the next call: a caller summarising many
// columns touches fresh pages once, not once per column).
Statistics compute_statistics(std::span<const double> values, const StatisticsOptions& options,
                              std::span<const std::uint8_t> degenerate, std::vector<double>& buffer);

// Linear-interpolation percentile of ascending `sorted` values, q in [0, 1].
double percentile_of_sorted(std::span<const double> sorted, double q);

}  // namespace hq
