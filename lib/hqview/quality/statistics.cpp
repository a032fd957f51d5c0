#include "hqview/quality/statistics.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/quality/corner_jacobian.h"

namespace hq {
namespace {

// The double's bits as an unsigned key in the same order as the values
// (negatives flipped whole, positives get the sign bit): -0.0 before +0.0.
inline std::uint64_t order_key(double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
}

// The bucket of an order key: the keys of negative values (below 2^63) and
// those of positive values each take their own run of buckets, evenly over
// their own key range, so values of one sign keep the bucket resolution
// when the other sign is present too (a key range spanning both signs
// would put every value of [0.5, 1) into one bucket of 2,048).
class KeyBuckets {
 public:
  static constexpr std::uint64_t kPositive = std::uint64_t{1} << 63;
  void include(std::uint64_t k) {
    Side& s = side(k);
    s.lo = std::min(s.lo, k);
    s.hi = std::max(s.hi, k);
  }
  // The keys `other` included, as if included here (before finish()).
  void merge(const KeyBuckets& other) {
    for (auto [mine, theirs] : {std::pair{&negative_, &other.negative_}, std::pair{&positive_, &other.positive_}}) {
      mine->lo = std::min(mine->lo, theirs->lo);
      mine->hi = std::max(mine->hi, theirs->hi);
    }
  }
  // Fixes the buckets: 2^10 a side, 2^11 when one side is empty. Few enough
  // that the bucket offsets stay in the L1 cache while the values are
  // scattered (2^16 buckets, until 2026-12-06, missed it on every value:
  // the 22 metrics' statistics of 363,520 hexes took 15 % longer); each
  // bucket is then sorted by radix_sort_by_key's own finer buckets.
  std::size_t finish() {
    const bool both = negative_.lo <= negative_.hi && positive_.lo <= positive_.hi;
    for (Side* s : {&negative_, &positive_}) {
      if (s->lo > s->hi) continue;
      s->shift = std::max(0, static_cast<int>(std::bit_width(s->hi - s->lo)) - (both ? 10 : 11));
      s->count = static_cast<std::size_t>((s->hi - s->lo) >> s->shift) + 1;
    }
    return negative_.count + positive_.count;
  }
  std::size_t operator()(std::uint64_t k) const {
    return k < kPositive ? static_cast<std::size_t>((k - negative_.lo) >> negative_.shift)
                         : negative_.count + static_cast<std::size_t>((k - positive_.lo) >> positive_.shift);
  }

 private:
  struct Side {
    std::uint64_t lo = ~std::uint64_t{0}, hi = 0;
    int shift = 0;
    std::size_t count = 0;
  };
  Side& side(std::uint64_t k) { return k < kPositive ? negative_ : positive_; }
  Side negative_, positive_;
};

// Ascending by order key, by insertion: the sort of the smallest ranges.
void insertion_sort_by_key(std::span<double> v) {
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double x = v[i];
    const std::uint64_t k = order_key(x);
    std::size_t j = i;
    for (; j > 0 && order_key(v[j - 1]) > k; --j) v[j] = v[j - 1];
    v[j] = x;
  }
}

constexpr std::size_t kInsertionSortMax = 16;

// Ascending by order key, most significant digits first: the range's keys
// are counted into about one bucket per value over their own [min, max]
// (at most 2^16), scattered through `scratch`, and each bucket of more than
// one value sorted the same way. Every level narrows a bucket's key range
// by at least 2^(bits-1), so the depth is bounded; equal values end a
// bucket at once (min == max). `scratch` is reused by the levels below.
void radix_sort_by_key(std::span<double> v, std::vector<double>& scratch) {
  if (v.size() <= kInsertionSortMax) {
    insertion_sort_by_key(v);
    return;
  }
  std::uint64_t lo = ~std::uint64_t{0}, hi = 0;
  for (double x : v) {
    const std::uint64_t k = order_key(x);
    lo = std::min(lo, k);
    hi = std::max(hi, k);
  }
  if (lo == hi) return;
  const int bits = std::min(16, static_cast<int>(std::bit_width(v.size())));
  const int shift = std::max(0, static_cast<int>(std::bit_width(hi - lo)) - bits);
  const std::size_t num_buckets = static_cast<std::size_t>((hi - lo) >> shift) + 1;
  const auto bucket = [&](double x) { return static_cast<std::size_t>((order_key(x) - lo) >> shift); };
  // end[b]: first the count of bucket b-1, then its start, then (after the
  // scatter) the end of bucket b.
  std::vector<std::size_t> end(num_buckets + 1, 0);
  for (double x : v) ++end[bucket(x) + 1];
  for (std::size_t b = 0; b < num_buckets; ++b) end[b + 1] += end[b];
  if (scratch.size() < v.size()) scratch.resize(v.size());
  for (double x : v) scratch[end[bucket(x)]++] = x;
  std::copy(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(v.size()), v.begin());
  for (std::size_t b = 0, begin = 0; b < num_buckets; begin = end[b++])
    if (end[b] - begin > 1) radix_sort_by_key(v.subspan(begin, end[b] - begin), scratch);
}

// Inputs of at least this many kept values sort their buckets in parallel.
constexpr std::size_t kParallelSortMin = 1 << 20;

// The values kept by the statistics (not NaN, not degenerate), ascending,
// in one array, without sorting them whole: the range of their order keys
// (`buckets`, from the caller's pass), a pass counting them into up to 2^11
// buckets of that range (monotone in the value), a second scattering them
// into place, and each bucket sorted on its own by its keys' digits
// (radix_sort_by_key), in parallel on large inputs. The array is the one
// std::sort gives, but for the relative order of -0.0 and +0.0 (compare
// equal, add up the same), so every sum and percentile is the same for any
// thread count. Memory: the output array, the bucket offsets, and scratch
// as large as the largest bucket.
// Large inputs count and scatter in this many slices of the values at once
// (a fixed number, not one per thread: the same work for any thread count;
// the scatter keeps each bucket's values in input order either way).
constexpr std::size_t kNumSlices = 16;

template <class IsKept>
void sorted_kept_values(std::span<const double> values, IsKept is_kept, std::size_t num_kept, KeyBuckets& buckets,
                        std::vector<double>& out) {
  // A buffer too small is replaced, its old values not copied along.
  if (out.capacity() < num_kept) out.clear();
  out.resize(num_kept);
  if (num_kept == 0) return;
  const std::size_t num_buckets = buckets.finish();
  std::vector<std::size_t> start(num_buckets + 1, 0);
  const auto bucket = [&](double v) { return buckets(order_key(v)); };
  if (values.size() < kParallelSortMin) {
    for (std::size_t i = 0; i < values.size(); ++i)
      if (is_kept(i)) ++start[bucket(values[i]) + 1];
    for (std::size_t b = 0; b < num_buckets; ++b) start[b + 1] += start[b];
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < values.size(); ++i)
      if (is_kept(i)) out[next[bucket(values[i])]++] = values[i];
  } else {
    // Per slice: its count in every bucket, then (prefix sums over buckets,
    // then slices) where its values of each bucket go.
    const std::size_t slice = (values.size() + kNumSlices - 1) / kNumSlices;
    std::vector<std::size_t> next(kNumSlices * num_buckets, 0);
    const auto for_each_slice = [&](auto body) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kNumSlices, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k)
          body(k, k * slice, std::min(values.size(), (k + 1) * slice), next.data() + k * num_buckets);
      });
    };
    for_each_slice([&](std::size_t, std::size_t begin, std::size_t end, std::size_t* counts) {
      for (std::size_t i = begin; i < end; ++i)
        if (is_kept(i)) ++counts[bucket(values[i])];
    });
    std::size_t at = 0;
    for (std::size_t b = 0; b < num_buckets; ++b) {
      start[b] = at;
      for (std::size_t k = 0; k < kNumSlices; ++k) {
        const std::size_t count = next[k * num_buckets + b];
        next[k * num_buckets + b] = at;
        at += count;
      }
    }
    start[num_buckets] = at;
    for_each_slice([&](std::size_t, std::size_t begin, std::size_t end, std::size_t* offsets) {
      for (std::size_t i = begin; i < end; ++i)
        if (is_kept(i)) out[offsets[bucket(values[i])]++] = values[i];
    });
  }
  const auto sort_buckets = [&](std::size_t first, std::size_t last) {
    std::vector<double> scratch;
    for (std::size_t b = first; b < last; ++b)
      if (start[b + 1] - start[b] > 1)
        radix_sort_by_key(std::span<double>(out).subspan(start[b], start[b + 1] - start[b]), scratch);
  };
  if (num_kept < kParallelSortMin)
    sort_buckets(0, num_buckets);
  else
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_buckets, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) { sort_buckets(r.begin(), r.end()); });
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
  std::vector<double> buffer;
  return compute_statistics(values, options, degenerate, buffer);
}

Statistics compute_statistics(std::span<const double> values, const StatisticsOptions& options,
                              std::span<const std::uint8_t> degenerate, std::vector<double>& buffer) {
  Statistics s;
  // Kept: finite, not Verdict's sentinel, not flagged degenerate.
  const auto is_kept = [&](std::size_t i) {
    const double v = values[i];
    return !std::isnan(v) && std::abs(v) < kVerdictDegenerate && (degenerate.empty() || degenerate[i] == 0);
  };
  std::size_t num_kept = 0;
  KeyBuckets buckets;
  // The kept values' count and key range, the others counted (by slices on
  // large inputs: counts, minima and maxima do not depend on the order).
  const auto scan = [&](std::size_t begin, std::size_t end, std::size_t& kept, std::int64_t& degenerate,
                        KeyBuckets& range) {
    for (std::size_t i = begin; i < end; ++i) {
      if (is_kept(i)) {
        ++kept;
        range.include(order_key(values[i]));
      } else if (!std::isnan(values[i])) {
        ++degenerate;
      }
    }
  };
  if (values.size() < kParallelSortMin) {
    scan(0, values.size(), num_kept, s.num_degenerate, buckets);
  } else {
    struct Slice {
      std::size_t kept = 0;
      std::int64_t degenerate = 0;
      KeyBuckets range;
    };
    std::array<Slice, kNumSlices> slices;
    const std::size_t slice = (values.size() + kNumSlices - 1) / kNumSlices;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kNumSlices, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k)
        scan(k * slice, std::min(values.size(), (k + 1) * slice), slices[k].kept, slices[k].degenerate,
             slices[k].range);
    });
    for (const Slice& part : slices) {
      num_kept += part.kept;
      s.num_degenerate += part.degenerate;
      buckets.merge(part.range);
    }
  }
  sorted_kept_values(values, is_kept, num_kept, buckets, buffer);
  const std::vector<double>& kept = buffer;
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
  // Values outside the range go to the end bins; the last edge is inclusive.
  // The bin is monotone in the value (each operation rounds monotonically),
  // so on the ascending values each bin is a run, found by bisection.
  const auto bin_of = [&](double v) {
    const double t = (v - lo) / (hi - lo) * bins;
    return std::clamp(static_cast<int>(std::floor(t)), 0, bins - 1);
  };
  auto run_begin = kept.begin();
  for (int b = 0; b < bins; ++b) {
    const auto run_end = std::partition_point(run_begin, kept.end(), [&](double v) { return bin_of(v) <= b; });
    s.histogram.counts[static_cast<std::size_t>(b)] = run_end - run_begin;
    run_begin = run_end;
  }
  return s;
}

}  // namespace hq
