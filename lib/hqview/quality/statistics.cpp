#include "hqview/quality/statistics.h"

#include <algorithm>
#include <cmath>

#include "hqview/quality/corner_jacobian.h"

namespace hq {

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
  std::sort(kept.begin(), kept.end());
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
