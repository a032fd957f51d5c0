#include "hqview/quality/statistics.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "hqview/quality/corner_jacobian.h"

namespace hq {
namespace {

// The double's bits as an unsigned key in the same order as the values
// (negatives flipped whole, positives get the sign bit): -0.0 before +0.0.
inline std::uint64_t order_key(double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
}

// Ascending order of finite doubles by LSD radix sort on order_key: 11-bit
// digits, 6 passes, a pass skipped when every key shares its digit (the high
// digits of values in a narrow range). Linear in the count: the summaries of
// 22 metrics over millions of cells are not dominated by sorting, and the
// order (hence every sum and percentile) is that of std::sort but for the
// relative order of -0.0 and +0.0, which compare equal.
void radix_sort(std::vector<double>& values) {
  constexpr int kBits = 11, kPasses = 6;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  const std::size_t n = values.size();
  if (n < 256) {
    std::sort(values.begin(), values.end());
    return;
  }
  std::vector<std::uint64_t> keys(n), scratch(n);
  std::vector<std::array<std::size_t, kBuckets>> counts(kPasses);
  for (auto& c : counts) c.fill(0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = order_key(values[i]);
    keys[i] = k;
    for (int p = 0; p < kPasses; ++p) ++counts[static_cast<std::size_t>(p)][(k >> (p * kBits)) & (kBuckets - 1)];
  }
  for (int p = 0; p < kPasses; ++p) {
    auto& c = counts[static_cast<std::size_t>(p)];
    const int shift = p * kBits;
    if (c[(keys[0] >> shift) & (kBuckets - 1)] == n) continue;  // one digit for all
    std::size_t offset = 0;
    for (std::size_t& count : c) offset += std::exchange(count, offset);
    for (std::size_t i = 0; i < n; ++i) scratch[c[(keys[i] >> shift) & (kBuckets - 1)]++] = keys[i];
    keys.swap(scratch);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = keys[i];
    values[i] = std::bit_cast<double>((k >> 63) != 0 ? k & ~(std::uint64_t{1} << 63) : ~k);
  }
}

}  // namespace

double percentile_of_sorted(std::span<const double> sorted, double q) {
  if (sorted.empty()) return 0.0;
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double t = pos - static_cast<double>(lo);
  return sorted[lo] + t * (sorted[hi] - sorted[lo]);
}

Statistics compute_statistics(std::span<const double> values, const StatisticsOptions& options,
                              std::span<const std::uint8_t> degenerate) {
  Statistics s;
  std::vector<double> kept;
  kept.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (std::isnan(v)) continue;
    if (std::abs(v) >= kVerdictDegenerate || (!degenerate.empty() && degenerate[i])) {
      ++s.num_degenerate;
      continue;
    }
    kept.push_back(v);
  }
  radix_sort(kept);
  s.count = static_cast<std::int64_t>(kept.size());

  const int bins = std::max(1, options.histogram_bins);
  const double lo = options.histogram_min.value_or(kept.empty() ? 0.0 : kept.front());
  double hi = options.histogram_max.value_or(kept.empty() ? 1.0 : kept.back());
  if (!(hi > lo)) hi = lo + 1.0;
  s.histogram.edges.resize(static_cast<std::size_t>(bins) + 1);
  for (int b = 0; b <= bins; ++b) s.histogram.edges[static_cast<std::size_t>(b)] = lo + (hi - lo) * b / bins;
  s.histogram.counts.assign(static_cast<std::size_t>(bins), 0);
  if (kept.empty()) return s;

  // Sum in ascending order: the same bytes for any thread count or input order.
  double sum = 0.0;
  for (double v : kept) sum += v;
  s.mean = sum / static_cast<double>(kept.size());
  double squares = 0.0;
  for (double v : kept) squares += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(squares / static_cast<double>(kept.size()));
  s.min = kept.front();
  s.max = kept.back();
  s.p01 = percentile_of_sorted(kept, 0.01);
  s.p05 = percentile_of_sorted(kept, 0.05);
  s.p50 = percentile_of_sorted(kept, 0.50);
  s.p95 = percentile_of_sorted(kept, 0.95);
  s.p99 = percentile_of_sorted(kept, 0.99);
  s.num_inverted = std::upper_bound(kept.begin(), kept.end(), 0.0) - kept.begin();
  for (double v : kept) {
    // Values outside the range go to the end bins; the last edge is inclusive.
    const double t = (v - lo) / (hi - lo) * bins;
    const int b = std::clamp(static_cast<int>(std::floor(t)), 0, bins - 1);
    ++s.histogram.counts[static_cast<std::size_t>(b)];
  }
  return s;
}

}  // namespace hq
